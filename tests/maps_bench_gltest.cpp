// `tallow probe maps` through the executable: the JSON contract at tiny sizes (K 1,2; N 1,2; 32²
// maps), the maps' memory against the texture formats of sss/maps/radiosity_maps.cpp, one-line errors
// for bad input.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "app/commands/maps_bench_command.h"
#include "support/run_tallow.h"
#include "support/temp_dir.h"

namespace tallow {
namespace {

using test::runTallow;

/// The maps of sss/maps/radiosity_maps.cpp: K layers of RGBA32F (16 bytes) with the full mip chain
/// (floor(log2 size) + 1 levels, each halving the edge), plus K layers of DEPTH_COMPONENT32F
/// (4 bytes) without mipmaps.
std::size_t expectedMapBytes(std::size_t k, std::size_t size) {
  std::size_t colour = 0;
  for (std::size_t s = size;; s /= 2) {
    colour += s * s;
    if (s == 1) break;
  }
  return k * colour * 16 + k * size * size * 4;
}

TEST(MapsBench, TinyRunWritesFourRowsWithPositiveTimesAndExactMemory) {
  test::TempDir dir;
  const auto out = dir.path() / "maps.json";
  const auto r = runTallow({"probe", "maps", "--preset", "bunny", "--size", "64x36", "--k", "1,2", "--n", "1,2",
                            "--map-size", "32", "--repeats", "2", "--set", "sss.light_map_size=32", "--out",
                            out.string()});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  std::ifstream in(out);
  nlohmann::json j;
  ASSERT_NO_THROW(j = nlohmann::json::parse(in));
  ASSERT_TRUE(j.contains("gpu"));
  EXPECT_FALSE(j["gpu"]["GL_RENDERER"].get<std::string>().empty());
  EXPECT_EQ(j["preset"], "bunny");
  EXPECT_EQ(j["settings"]["map_size"], 32);
  EXPECT_EQ(j["settings"]["width"], 64);
  EXPECT_EQ(j["settings"]["height"], 36);
  EXPECT_EQ(j["settings"]["repeats"], 2);
  ASSERT_EQ(j["rows"].size(), 4u);
  // Rows in the order of the product K × N.
  const int ks[] = {1, 1, 2, 2}, ns[] = {1, 2, 1, 2};
  for (std::size_t i = 0; i < 4; ++i) {
    const auto& row = j["rows"][i];
    EXPECT_EQ(row["k"], ks[i]);
    EXPECT_EQ(row["n"], ns[i]);
    for (const char* key : {"light_gbuffer_ms", "maps_ms", "surface_ms", "frame_gpu_ms", "frame_wall_ms"}) {
      ASSERT_TRUE(row.contains(key)) << key;
      EXPECT_TRUE(std::isfinite(row[key].get<double>())) << key;
    }
    // Timestamp spans: sss.maps and surface draw every frame; the light G-buffers are drawn once, in
    // the warm-up frame (the timed frames keep them), and that is the time reported.
    EXPECT_GT(row["maps_ms"].get<double>(), 0.0) << i;
    EXPECT_GT(row["surface_ms"].get<double>(), 0.0) << i;
    EXPECT_GT(row["first_frame"]["light_gbuffer_ms"].get<double>(), 0.0) << i;
    EXPECT_EQ(row["light_gbuffer_ms"], row["first_frame"]["light_gbuffer_ms"]) << i;
    EXPECT_EQ(row["map_bytes"].get<std::size_t>(), expectedMapBytes(static_cast<std::size_t>(ks[i]), 32)) << i;
    EXPECT_GT(row["sss_bytes"].get<std::size_t>(), row["map_bytes"].get<std::size_t>()) << i;  // + light G-buffers
    EXPECT_EQ(row["map_texels"].get<std::size_t>(), static_cast<std::size_t>(ks[i]) * 32 * 32) << i;
    EXPECT_GT(row["shaded_texels"].get<std::size_t>(), 0u) << i;
    EXPECT_LE(row["shaded_texels"].get<std::size_t>(), row["map_texels"].get<std::size_t>()) << i;
    EXPECT_EQ(row["frames_accumulated"], 3) << i;  // warm-up + 2 timed frames, no restart
    EXPECT_GT(row["evaluations_per_s"].get<double>(), 0.0) << i;
    EXPECT_DOUBLE_EQ(row["evaluations_per_frame"].get<double>(),
                     row["shaded_texels"].get<double>() * 3.0 * ns[i] * row["lights"].get<double>()) << i;
  }
  ASSERT_TRUE(j.contains("fit"));
  for (const char* key : {"intercept_ms", "slope_ms", "r2"}) EXPECT_TRUE(std::isfinite(j["fit"][key].get<double>())) << key;
  for (const char* key : {"intercept_ms", "per_map_ms", "per_sample_ms", "r2"})
    EXPECT_TRUE(std::isfinite(j["fit_k_kn"][key].get<double>())) << key;
}

TEST(MapsBench, LinearFitRecoversALine) {
  const auto f = app::fitLine({1, 2, 4, 8}, {3.5, 5.5, 9.5, 17.5});
  EXPECT_NEAR(f.intercept, 1.5, 1e-12);
  EXPECT_NEAR(f.slope, 2.0, 1e-12);
  EXPECT_NEAR(f.r2, 1.0, 1e-12);
  const auto p = app::fitPlane({1, 1, 2, 2, 3}, {1, 2, 2, 4, 9}, {1 + 2 * 1 + 3 * 1.0, 1 + 2 * 1 + 3 * 2.0,
                                                                  1 + 2 * 2 + 3 * 2.0, 1 + 2 * 2 + 3 * 4.0,
                                                                  1 + 2 * 3 + 3 * 9.0});
  EXPECT_NEAR(p.intercept, 1.0, 1e-9);
  EXPECT_NEAR(p.a, 2.0, 1e-9);
  EXPECT_NEAR(p.b, 3.0, 1e-9);
  EXPECT_NEAR(p.r2, 1.0, 1e-12);
  const auto g = app::fitLine({1, 2, 3}, {1, 3, 2});
  EXPECT_NEAR(g.slope, 0.5, 1e-12);
  EXPECT_NEAR(g.r2, 0.25, 1e-12);
}

TEST(MapsBench, BadInputGivesOneLineAndExitOne) {
  test::TempDir dir;
  const std::string out = (dir.path() / "x.json").string();
  const std::vector<std::string> tiny = {"--size", "64x36", "--map-size", "32", "--repeats", "1", "--out", out};
  auto with = [&](std::vector<std::string> args) {
    args.insert(args.begin(), {"probe", "maps"});
    args.insert(args.end(), tiny.begin(), tiny.end());
    return args;
  };
  const std::vector<std::vector<std::string>> cases = {
      with({"--preset", "bunny", "--k", "0", "--n", "1"}),
      with({"--preset", "bunny", "--k", "1", "--n", "4097"}),  // the registry's sss.samples maximum is 4096
      with({"--preset", "bunny", "--k", "1", "--n", "0"}),
      with({"--preset", "bunny", "--k", "257", "--n", "1"}),
      with({"--preset", "no-such-preset", "--k", "1", "--n", "1"}),
      {"probe", "maps", "--preset", "bunny", "--k", "1", "--n", "1", "--repeats", "0", "--out", out},
  };
  for (const auto& args : cases) {
    const auto r = runTallow(args);
    std::string joined;
    for (const auto& a : args) joined += a + " ";
    EXPECT_EQ(r.exitCode, 1) << joined;
    EXPECT_EQ(test::lineCount(r.err), 1) << joined << "\n" << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace tallow
