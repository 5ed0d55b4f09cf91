// `tallow bench` through the real executable on the slab at a tiny size: the table's shape, an
// error recomputed here from the written last frame, a method ordering with an independent reason,
// and one line + non-zero exit + nothing written for each kind of bad input.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "gpu/image_io.h"
#include "support/run_tallow.h"
#include "support/temp_dir.h"

namespace tallow {
namespace {

using test::runTallow;

constexpr const char* kSize = "8x6";
/// Small maps and few accumulated frames keep each row to a few llvmpipe frames.
const std::vector<std::string> kSmall = {"--preset", "slab", "--size", kSize, "--set", "sss.map_size=64",
                                         "--set", "sss.light_map_size=64", "--set", "sss.frames=3"};

std::vector<std::string> concat(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream s(line);
  std::string c;
  while (std::getline(s, c, ',')) cells.push_back(c);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

/// bench.csv as one map (column → cell) per row.
std::vector<std::map<std::string, std::string>> readCsv(const std::filesystem::path& file, std::vector<std::string>& header) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  header = split(line);
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    const auto cells = split(line);
    EXPECT_EQ(cells.size(), header.size()) << line;
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < cells.size() && i < header.size(); ++i) row[header[i]] = cells[i];
    rows.push_back(row);
  }
  return rows;
}

/// A reference of the slab at kSize, shared by the tests of this file (the integrator's 4 passes).
class BenchCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new test::TempDir();
    const auto r =
        runTallow({"reference", "--preset", "slab", "--size", kSize, "--spp", "4", "--out", ref().string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  static std::filesystem::path ref() { return dir_->path() / "ref.exr"; }
  static test::TempDir* dir_;
};
test::TempDir* BenchCli::dir_ = nullptr;

TEST_F(BenchCli, TableHasOneRowPerMethodAndSettingWithFiniteErrors) {
  test::TempDir dir;
  const auto out = dir.path() / "bench";
  const auto r = runTallow(concat({"bench"}, concat(kSmall, {"--reference", ref().string(), "--methods",
                                                             "radiosity-maps,albedo", "--sweep", "sss.maps=4,8",
                                                             "--frames", "5", "--out", out.string()})));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  std::vector<std::string> header;
  const auto rows = readCsv(out / "bench.csv", header);
  // Albedo reads no sss.* key (its passes declare none): one row for it, not one per K, and its
  // sss.maps cell empty (issue 19: a sweep applies only to the methods that read its key).
  ASSERT_EQ(rows.size(), 3u);
  for (const char* column : {"row", "method", "sss.maps", "frames", "first_wall_ms", "first_rel_rmse", "median_wall_ms",
                             "median_accumulating_wall_ms", "median_converged_wall_ms", "gpu_ms_surface", "last_rmse",
                             "last_rel_rmse", "last_max_error", "object_pixels", "gpu_bytes", "maps_bytes", "triangles"})
    EXPECT_NE(std::find(header.begin(), header.end(), column), header.end()) << column;
  std::map<std::string, double> relByMethod;  // the larger over the two K
  std::map<std::string, int> seen;  // method and K
  for (const auto& row : rows) {
    const std::string& method = row.at("method");
    seen[method + " " + row.at("sss.maps")]++;
    // sss.frames = 3: a progressive method accumulates 3 frames, then needs 2 converged ones.
    EXPECT_GE(std::stoi(row.at("frames")), 5);
    for (const char* column : {"first_wall_ms", "first_rmse", "last_rmse", "last_rel_rmse", "last_max_error"}) {
      const double v = std::stod(row.at(column));
      EXPECT_TRUE(std::isfinite(v) && v >= 0.0) << column << " = " << row.at(column);
    }
    if (method == "radiosity-maps") {
      EXPECT_GE(std::stoi(row.at("converged_frames")), 2);
      EXPECT_FALSE(row.at("maps_bytes").empty());
    }
    relByMethod[method] = std::max(relByMethod[method], std::stod(row.at("last_rel_rmse")));

    // The bench's RMSE recomputed from the float EXR of the last frame, with the metric's own
    // definition written out here: object pixels are those of the reference's standard-error alpha.
    const gpu::Image last = gpu::readExr(out / "rows" / row.at("row") / "last.exr");
    const gpu::Image reference = gpu::readExr(ref());
    const gpu::Image stderrImage = gpu::readExr(dir_->path() / "ref_stderr.exr");
    ASSERT_EQ(last.pixels.size(), reference.pixels.size());
    double sum = 0.0, sumRef = 0.0;
    int n = 0;
    for (std::size_t i = 0; i < last.pixels.size(); ++i) {
      if (stderrImage.pixels[i].a < 0.5f) continue;
      for (int c = 0; c < 3; ++c) {
        const double d = double(last.pixels[i][c]) - double(reference.pixels[i][c]);
        sum += d * d;
        sumRef += double(reference.pixels[i][c]) * reference.pixels[i][c];
      }
      ++n;
    }
    ASSERT_GT(n, 0);
    EXPECT_EQ(std::stoi(row.at("object_pixels")), n);
    const double rmse = std::sqrt(sum / n);
    EXPECT_NEAR(std::stod(row.at("last_rmse")), rmse, 1e-5 * rmse);
    EXPECT_NEAR(std::stod(row.at("last_rel_rmse")), rmse / std::sqrt(sumRef / n), 1e-5 * rmse / std::sqrt(sumRef / n));
  }
  EXPECT_EQ(seen, (std::map<std::string, int>{{"albedo ", 1}, {"radiosity-maps 4", 1}, {"radiosity-maps 8", 1}}));
  // Albedo shades the slab as a Lambertian surface, without the light that scatters beneath it;
  // the reference has that light, so albedo must be further from it than the radiosity maps.
  EXPECT_GT(relByMethod["albedo"], relByMethod["radiosity-maps"]);

  // convergence.csv: one line per timed frame of every row.
  std::vector<std::string> convergenceHeader;
  const auto frames = readCsv(out / "convergence.csv", convergenceHeader);
  std::size_t expected = 0;
  for (const auto& row : rows) expected += std::stoul(row.at("frames"));
  EXPECT_EQ(frames.size(), expected);
  // One folder of pictures per row.
  for (const char* file : {"bench.json", "rows/radiosity-maps_sss.maps-4/first.png", "rows/radiosity-maps_sss.maps-4/last.png",
                           "rows/albedo/last.exr"})
    EXPECT_TRUE(std::filesystem::is_regular_file(out / file)) << file;
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(out / "rows"), std::filesystem::directory_iterator()), 3);

  // 8x6 pixels hold a few dozen object pixels: said on stderr and in bench.json.
  EXPECT_NE(r.err.find("tallow: warning: bench: only " + rows[0].at("object_pixels") + " object pixels are compared"),
            std::string::npos)
      << r.err;
  std::ifstream in(out / "bench.json");
  const nlohmann::json bench = nlohmann::json::parse(in);
  ASSERT_EQ(bench["warnings"].size(), 1u);
  EXPECT_NE(bench["provenance"]["tallow_version"].get<std::string>().find("git"), std::string::npos);
  EXPECT_EQ(bench["run"]["state"], "complete");
  // The reference's ε on every row, on the console and in the table.
  for (const auto& row : rows) EXPECT_FALSE(row.at("reference_rel_error").empty()) << row.at("row");
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 4) << "three rows and the summary:\n" << r.out;
  EXPECT_NE(r.out.find("(reference ε "), std::string::npos) << r.out;

  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) GTEST_SKIP() << "gnuplot is not installed: no plots";
  // The plot's script: one series per method, each its own colour and marker; every point labelled
  // with its sweep value (placed clear of the others) where it has one; a dashed line at the reference's ε.
  std::ifstream gp(out / "speed_error.gp");
  const std::string script((std::istreambuf_iterator<char>(gp)), std::istreambuf_iterator<char>());
  const std::regex series("with points pt ([0-9]+) ps [0-9.]+ lc rgb '(#[0-9A-Fa-f]+)' title '([a-z-]+)'");
  std::map<std::string, std::pair<std::string, std::string>> styles;
  for (auto it = std::sregex_iterator(script.begin(), script.end(), series); it != std::sregex_iterator(); ++it)
    styles[(*it)[3]] = {(*it)[1], (*it)[2]};
  ASSERT_EQ(styles.size(), 2u) << script;
  EXPECT_NE(styles["albedo"].first, styles["radiosity-maps"].first);
  EXPECT_NE(styles["albedo"].second, styles["radiosity-maps"].second);
  const std::regex label("set label '[48]' at screen");
  EXPECT_EQ(std::distance(std::sregex_iterator(script.begin(), script.end(), label), std::sregex_iterator()), 2) << script;
  EXPECT_NE(script.find("set label 'reference ε "), std::string::npos) << script;
  EXPECT_NE(script.find("nohead dt 2"), std::string::npos) << "the ε line";
  EXPECT_TRUE(std::filesystem::is_regular_file(out / "speed_error.png"));
  // Each row's comparison picture: reference, first and last frames and their differences in false colour.
  const gpu::Image figure = gpu::readPng(out / "rows/radiosity-maps_sss.maps-4/comparison.png");
  EXPECT_GT(figure.width, 3 * 240) << "three panels, each enlarged to at least 240 pixels";
}

TEST_F(BenchCli, BadInputGivesOneLineAndWritesNothing) {
  test::TempDir dir;
  const auto out = dir.path() / "bench";
  const std::string refArg = ref().string();
  // A reference whose standard-error image is cut short.
  std::filesystem::copy_file(ref(), dir.path() / "broken.exr");
  {
    std::ifstream in(dir_->path() / "ref_stderr.exr", std::ios::binary);
    std::string bytes(300, '\0');
    in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    dir.write("broken_stderr.exr", bytes);
  }
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--reference", refArg, "--methods", "radiosity-mapz"}, "method"},
      {{"--reference", refArg, "--frames", "4"}, "--frames"},
      {{"--reference", refArg, "--sweep", "sss.maps"}, "--sweep"},
      {{"--reference", refArg, "--sweep", "sss.maps="}, "--sweep"},
      {{"--reference", refArg, "--sweep", "sss.mpas=4,8"}, "sss.mpas"},
      {{"--reference", refArg, "--sweep", "sss.maps=4,0"}, "sss.maps"},
      {{"--reference", refArg, "--sweep", "material=Marble,Skimmilk"}, "material"},
      {{"--reference", (dir.path() / "missing.exr").string()}, "missing.exr"},
      {{"--reference", refArg, "--size", "10x6"}, "10x6"},
      {{"--reference", (dir.path() / "broken.exr").string()}, "broken_stderr.exr"},
      {{}, "--reference"},
      {{"--ref-spp", "0"}, "--ref-spp"},
  };
  for (const auto& [extra, expected] : cases) {
    std::vector<std::string> args = {"bench", "--preset", "slab", "--out", out.string()};
    if (std::find(extra.begin(), extra.end(), "--size") == extra.end()) args.insert(args.end(), {"--size", kSize});
    args.insert(args.end(), extra.begin(), extra.end());
    const auto r = runTallow(args);
    std::string joined;
    for (const auto& a : extra) joined += a + " ";
    EXPECT_NE(r.exitCode, 0) << joined;
    EXPECT_EQ(test::lineCount(r.err), 1) << joined << "\n" << r.err;
    EXPECT_NE(r.err.find(expected), std::string::npos) << joined << "\n" << r.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << joined;
  }
  // An --out whose parent is a file.
  const auto file = dir.write("file", "x");
  const auto r = runTallow({"bench", "--preset", "slab", "--size", kSize, "--reference", refArg, "--out",
                            (file / "bench").string()});
  EXPECT_NE(r.exitCode, 0);
  EXPECT_EQ(test::lineCount(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("is not a folder"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace tallow
