// `tallow probe bssrdf|profile` through the executable: the CSV contract, bad input, the GPU path.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "app/commands/bssrdf_csv.h"
#include "support/run_tallow.h"
#include "support/temp_dir.h"

namespace tallow {
namespace {

using test::runTallow;

const std::string kHeader(app::kBssrdfConfigColumns);

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::vector<double>> readValues(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, kHeader + ",sd,sd_clamped");
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::stringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  return rows;
}

const char* kConfigs =
    "0,0,0,0,0,1,0,0,1,1,0,0,0,0,1,0.01,1,0,1.3\n"
    "0,0,0,0,0,1,-0.5,0,0.8660254037844386,0.5,0.2,0,0,0,1,0.0021,2.19,0.3,1.5\n"
    "0,0,0,0,0,1,0.6,0,-0.8,2,0,0,0,0,1,0.1,0.5,-0.5,1.0\n";

TEST(ProbeCli, BssrdfWritesInputsAndBothValuesInFullPrecision) {
  test::TempDir dir;
  const auto in = dir.write("in.csv", kHeader + "\n" + kConfigs);
  for (const char* model : {"standard", "directional", "pbd"}) {
    const auto out = dir.path() / (std::string(model) + ".csv");
    const auto r = runTallow({"probe", "bssrdf", "--model", model, "--in", in.string(), "--out", out.string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto rows = readValues(out);
    ASSERT_EQ(rows.size(), 3u);
    for (const auto& row : rows) {
      ASSERT_EQ(row.size(), 21u);
      EXPECT_TRUE(std::isfinite(row[19]));
      EXPECT_EQ(row[20], std::max(0.0, row[19])) << model;  // the clamp of §6.1, and nothing else
    }
    EXPECT_EQ(rows[1][6], -0.5);  // inputs echoed exactly (17 significant digits)
    EXPECT_EQ(rows[1][8], 0.8660254037844386);
  }
}

TEST(ProbeCli, GpuAgreesWithCpuFloat) {
  test::TempDir dir;
  const auto in = dir.write("in.csv", kHeader + "\n" + kConfigs);
  for (const char* model : {"standard", "directional", "pbd"}) {
    const auto cpu = dir.path() / "cpu.csv";
    const auto gpu = dir.path() / "gpu.csv";
    ASSERT_EQ(runTallow({"probe", "bssrdf", "--model", model, "--precision", "float", "--in", in.string(), "--out",
                         cpu.string()}).exitCode, 0);
    const auto r = runTallow({"probe", "bssrdf", "--model", model, "--gpu", "--in", in.string(), "--out", gpu.string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto a = readValues(cpu), b = readValues(gpu);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(a[i][19], b[i][19], 1e-5 * std::abs(a[i][19]) + 1e-12) << model << " row " << i;
  }
}

TEST(ProbeCli, BadConfigurationsNameFileLineAndColumn) {
  test::TempDir dir;
  const auto out = dir.path() / "out.csv";
  struct Case {
    std::string text, expected;
  };
  const std::vector<Case> cases = {
      {"x,y\n", ":1: expected the header"},
      {kHeader + "\n0,0,0,0,0,1,0,0,1,1,0,0,0,0,1,0.01,1,0\n", ":2: expected 19 columns, found 18"},
      {kHeader + "\n\n0,0,0,0,0,1,0,0,1,1,0,0,0,0,1,abc,1,0,1.3\n", ":3: sigma_a: \"abc\" is not a finite number"},
      {kHeader + "\n0,0,0,0,0,1,0,0,1,1,0,0,0,0,1,0.01,1,0,-1.3\n", ":2: "},
      {kHeader + "\n0,0,0,0,0,1,0,0,1,1,0,0,0,0,1,0.01,1,1.0,1.3\n", ":2: "},
      {kHeader + "\n0,0,0,0,0,1,0,0,1,1,0,0,0,0,1,-0.01,1,0,1.3\n", ":2: "},
      {kHeader + "\n0,0,0,0,0,0,0,0,1,1,0,0,0,0,1,0.01,1,0,1.3\n", ":2: "},
      {"", ": empty file"},
  };
  for (const auto& c : cases) {
    const auto in = dir.write("bad.csv", c.text);
    const auto r = runTallow({"probe", "bssrdf", "--model", "directional", "--in", in.string(), "--out", out.string()});
    EXPECT_NE(r.exitCode, 0) << c.text;
    EXPECT_EQ(test::lineCount(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(in.string() + c.expected), std::string::npos) << r.err << " expected " << c.expected;
    EXPECT_FALSE(std::filesystem::exists(out)) << "no output for bad input";
  }
  const auto in = dir.write("ok.csv", kHeader + "\n" + kConfigs);
  auto r = runTallow({"probe", "bssrdf", "--model", "dipole", "--in", in.string(), "--out", out.string()});
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.err.find("--model"), std::string::npos) << r.err;
  r = runTallow({"probe", "bssrdf", "--model", "pbd", "--gpu", "--precision", "double", "--in", in.string(), "--out",
                 out.string()});
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.err.find("float"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(ProbeCli, ProfileWritesCsvAndMarksNegativeRegions) {
  test::TempDir dir;
  const auto out = dir.path() / "p";
  // Grazing incidence on a strongly absorbing medium: the directional dipole goes negative behind
  // the point of incidence (directional-dipole paper, Fig. 13).
  const auto r = runTallow({"probe", "profile", "--model", "directional", "--sigma-a", "0.1", "--sigma-s", "0.1",
                            "--theta", "85", "--extent", "10", "--bins", "40", "--out", out.string()});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  std::ifstream map(out / "profile_map.csv");
  std::string line;
  std::getline(map, line);
  EXPECT_EQ(line, "x_mm,y_mm,rd,negative");
  int rows = 0, negative = 0, negativeAhead = 0;
  while (std::getline(map, line)) {
    std::stringstream cells(line);
    std::string x, y, rd, neg;
    std::getline(cells, x, ',');
    std::getline(cells, y, ',');
    std::getline(cells, rd, ',');
    std::getline(cells, neg, ',');
    ++rows;
    EXPECT_EQ(neg == "1", std::stod(rd) < 0.0) << line;
    negative += neg == "1";
    negativeAhead += neg == "1" && std::stod(x) > 0.0;
  }
  EXPECT_EQ(rows, 40 * 40);
  EXPECT_GT(negative, 0);
  EXPECT_EQ(negativeAhead, 0) << "the negative lobe lies behind the incident ray (x < 0)";
  EXPECT_NE(slurp(out / "profile_x.csv").find("x_mm,rd,rd_stderr,negative"), std::string::npos);
}

}  // namespace
}  // namespace tallow
