// `tallow compare A.exr B.exr --json ERR.json`: A's error against B over a mask, as capture's
// per-frame "reference_error" has it, checked on images whose answers are worked out by hand.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <fstream>
#include <string>

#include "gpu/image_io.h"
#include "support/run_tallow.h"
#include "support/temp_dir.h"

namespace tallow {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::runTallow;

json readJsonFile(const fs::path& file) {
  std::ifstream in(file);
  return json::parse(in);
}

/// 16×12: the upper six rows at `upper`, the lower six at `lower` (grey, alpha 1).
gpu::Image halves(float upper, float lower) {
  gpu::Image image(16, 12);
  for (int y = 0; y < 12; ++y)
    for (int x = 0; x < 16; ++x) image.pixels[static_cast<std::size_t>(y * 16 + x)] = glm::vec4(glm::vec3(y < 6 ? upper : lower), 1.0f);
  return image;
}

TEST(CompareJson, ErrorsOfKnownImages) {
  test::TempDir dir;
  const fs::path a = dir.path() / "a.exr", b = dir.path() / "b.exr", spot = dir.path() / "spot.exr";
  gpu::writeExr(b, halves(1.0f, 2.0f), gpu::ExrPixelType::Float, {});
  gpu::writeExr(a, halves(1.1f, 1.8f), gpu::ExrPixelType::Float, {});
  auto r = runTallow({"compare", a.string(), b.string(), "--json", (dir.path() / "e.json").string()});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const json e = readJsonFile(dir.path() / "e.json")["error"];
  // Differences 0.1 and 0.2 on equal halves: RMSE √0.025, the reference's RMS √2.5: exactly 10%.
  EXPECT_NEAR(e["rel_rmse"].get<double>(), 0.1, 1e-6);
  EXPECT_NEAR(e["upper_mean_ratio"].get<double>(), 1.1, 1e-6);
  EXPECT_NEAR(e["lower_mean_ratio"].get<double>(), 0.9, 1e-6);
  EXPECT_NEAR(e["mean_ratio"].get<double>(), (1.1 + 1.8) / 3.0, 1e-6);
  EXPECT_EQ(e["pixels"], 16 * 12) << "no mask: every pixel";
  EXPECT_EQ(e["fireflies"], 0);

  // One pixel at 20 among ones: a firefly (above 4× its 5×5 median) in A, none in B.
  gpu::Image withSpot = halves(1.0f, 2.0f);
  withSpot.pixels[2 * 16 + 3] = glm::vec4(20.0f, 20.0f, 20.0f, 1.0f);
  gpu::writeExr(spot, withSpot, gpu::ExrPixelType::Float, {});
  r = runTallow({"compare", spot.string(), b.string(), "--json", (dir.path() / "f.json").string()});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const json f = readJsonFile(dir.path() / "f.json")["error"];
  EXPECT_EQ(f["fireflies"], 1);
  EXPECT_EQ(f["reference_fireflies"], 0);
  // Listed with its pixel, its ratio to its median (20 / 1) and the reference's own there (1 / 1).
  ASSERT_EQ(f["fireflies_not_in_reference"].size(), 1u);
  const json& spotted = f["fireflies_not_in_reference"][0];
  EXPECT_EQ(spotted["x"], 3);
  EXPECT_EQ(spotted["y"], 2);
  EXPECT_EQ(spotted["channel"], 0);
  EXPECT_NEAR(spotted["over_median"].get<double>(), 20.0, 1e-6);
  EXPECT_NEAR(spotted["reference_over_median"].get<double>(), 1.0, 1e-6);
  EXPECT_NEAR(spotted["over_reference"].get<double>(), 20.0, 1e-6);
  // Against itself it has the firefly too: none listed.
  r = runTallow({"compare", spot.string(), spot.string(), "--json", (dir.path() / "s.json").string()});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const json self = readJsonFile(dir.path() / "s.json")["error"];
  EXPECT_EQ(self["reference_fireflies"], 1);
  EXPECT_TRUE(self["fireflies_not_in_reference"].empty());

  // A mask marking only the lower half: only its pixels count.
  gpu::Image lowerOnly = halves(0.0f, 0.0f);
  for (int i = 6 * 16; i < 12 * 16; ++i) lowerOnly.pixels[static_cast<std::size_t>(i)].a = 1.0f;
  for (int i = 0; i < 6 * 16; ++i) lowerOnly.pixels[static_cast<std::size_t>(i)].a = 0.0f;
  gpu::writeExr(dir.path() / "mask.exr", lowerOnly, gpu::ExrPixelType::Float, {});
  r = runTallow({"compare", a.string(), b.string(), "--mask", (dir.path() / "mask.exr").string(), "--json",
                 (dir.path() / "g.json").string()});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const json g = readJsonFile(dir.path() / "g.json")["error"];
  EXPECT_EQ(g["pixels"], 16 * 6);
  EXPECT_NEAR(g["mean_ratio"].get<double>(), 0.9, 1e-6);

  // Bad input: one line, non-zero, nothing written.
  r = runTallow({"compare", a.string(), b.string()});
  EXPECT_NE(r.exitCode, 0);
  EXPECT_EQ(r.err, "tallow: compare: --out FIG.png, --json ERR.json or a threshold (--max-rel-rmse) is required\n");
  gpu::Image none = halves(0.0f, 0.0f);
  for (auto& p : none.pixels) p.a = 0.0f;
  gpu::writeExr(dir.path() / "none.exr", none, gpu::ExrPixelType::Float, {});
  r = runTallow({"compare", a.string(), b.string(), "--mask", (dir.path() / "none.exr").string(), "--json",
                 (dir.path() / "h.json").string()});
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.err.find("marks no pixel"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir.path() / "h.json"));
}

TEST(CompareThreshold, AGoldenImageTestPassesWithinAndFailsPastTheThresholds) {
  test::TempDir dir;
  const fs::path a = dir.path() / "a.exr", b = dir.path() / "b.exr", spot = dir.path() / "spot.exr";
  gpu::writeExr(b, halves(1.0f, 2.0f), gpu::ExrPixelType::Float, {});
  gpu::writeExr(a, halves(1.1f, 1.8f), gpu::ExrPixelType::Float, {});  // exactly 10% (above)
  // Identical files: exactly 0, no new firefly, exit 0 and one line on stdout.
  auto r = runTallow({"compare", b.string(), b.string(), "--max-rel-rmse", "0"});
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_NE(r.out.find("relative RMSE 0, 0 new fireflies"), std::string::npos) << r.out;
  // 10% against a 0.11 limit passes, against 0.09 fails with exit 3 and one line naming both.
  r = runTallow({"compare", a.string(), b.string(), "--max-rel-rmse", "0.11"});
  EXPECT_EQ(r.exitCode, 0) << r.err;
  r = runTallow({"compare", a.string(), b.string(), "--max-rel-rmse", "0.09", "--json", (dir.path() / "e.json").string()});
  EXPECT_EQ(r.exitCode, 3);
  EXPECT_EQ(r.err, "tallow: compare: " + a.string() + " differs from " + b.string() +
                       ": relative RMSE 0.1, 0 new fireflies (relative RMSE above --max-rel-rmse 0.09)\n");
  EXPECT_TRUE(fs::exists(dir.path() / "e.json")) << "the JSON asked for is written for the CI's artefacts";
  // A firefly that B lacks: counted as new (one), so --max-new-fireflies 0 fails and 1 passes;
  // against itself it is not new.
  gpu::Image withSpot = halves(1.0f, 2.0f);
  withSpot.pixels[2 * 16 + 3] = glm::vec4(20.0f, 20.0f, 20.0f, 1.0f);
  gpu::writeExr(spot, withSpot, gpu::ExrPixelType::Float, {});
  r = runTallow({"compare", spot.string(), b.string(), "--max-new-fireflies", "0"});
  EXPECT_EQ(r.exitCode, 3);
  EXPECT_NE(r.err.find("1 new firefly (more new fireflies than --max-new-fireflies 0)"), std::string::npos) << r.err;
  r = runTallow({"compare", spot.string(), b.string(), "--max-new-fireflies", "1"});
  EXPECT_EQ(r.exitCode, 0) << r.err;
  r = runTallow({"compare", spot.string(), spot.string(), "--max-new-fireflies", "0", "--json",
                 (dir.path() / "s.json").string()});
  EXPECT_EQ(r.exitCode, 0) << r.err;
  const json self = readJsonFile(dir.path() / "s.json")["error"];
  EXPECT_EQ(self["fireflies"], 1);
  EXPECT_EQ(self["new_fireflies"], 0);
  // Bad thresholds: one line, before anything is read.
  r = runTallow({"compare", a.string(), b.string(), "--max-rel-rmse", "-1"});
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_EQ(r.err, "tallow: --max-rel-rmse: must be a finite fraction >= 0, e.g. 0.02\n");
}

}  // namespace
}  // namespace tallow
