// `tallow probe extraction` through the executable: the JSON contract on a small case, GPU and CPU
// triangle counts on the same lattice, one-line errors for bad input.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "support/run_tallow.h"
#include "support/temp_dir.h"

namespace tallow {
namespace {

using test::runTallow;

TEST(ExtractionBench, SmallBlobWritesEveryKeyWithPositiveCounts) {
  test::TempDir dir;
  const auto out = dir.path() / "extraction.json";
  const auto r = runTallow({"probe", "extraction", "--fields", "blob", "--res", "32", "--repeats", "1", "--out", out.string()});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  std::ifstream in(out);
  const nlohmann::json j = nlohmann::json::parse(in);
  ASSERT_TRUE(j.contains("gpu"));
  EXPECT_FALSE(j["gpu"]["GL_RENDERER"].get<std::string>().empty());
  EXPECT_EQ(j["repeats"], 1);
  ASSERT_EQ(j["fields"].size(), 1u);
  const auto& field = j["fields"][0];
  EXPECT_EQ(field["field"], "blob");
  ASSERT_TRUE(field.contains("ratio_256_128"));
  EXPECT_TRUE(field["ratio_256_128"]["gpu_extract"].is_null());  // only 32³ was run
  ASSERT_EQ(field["rows"].size(), 1u);
  const auto& row = field["rows"][0];
  EXPECT_EQ(row["res"], 32);
  for (const char* key : {"sample_cpu_ms", "gpu_upload_ms", "gpu_extract_ms", "gpu_extract_wall_ms", "cpu_mesh_ms",
                          "gpu_triangles_per_s", "cpu_triangles_per_s"}) {
    ASSERT_TRUE(row.contains(key)) << key;
    EXPECT_TRUE(std::isfinite(row[key].get<double>())) << key;
    EXPECT_GE(row[key].get<double>(), 0.0) << key;
  }
  for (const char* key : {"gpu_triangles", "cpu_triangles", "gpu_vertices", "active_blocks", "blocks", "gpu_buffer_bytes"}) {
    ASSERT_TRUE(row.contains(key)) << key;
    EXPECT_GT(row[key].get<std::size_t>(), 0u) << key;
  }
  EXPECT_LE(row["active_blocks"].get<std::size_t>(), row["blocks"].get<std::size_t>());
  EXPECT_GT(row["cpu_mesh_ms"].get<double>(), 0.0);
  EXPECT_GT(row["gpu_extract_wall_ms"].get<double>(), 0.0);

  // Surface nets and OpenVDB's volumeToMesh on the same lattice: both two triangles per
  // sign-changing edge (OpenVDB splits its quads), so the counts agree closely.
  const double gpu = row["gpu_triangles"].get<double>(), cpu = row["cpu_triangles"].get<double>();
  EXPECT_NEAR(gpu, cpu, 0.1 * cpu) << "gpu " << gpu << " cpu " << cpu;
}

TEST(ExtractionBench, BadInputGivesOneLineAndNonZeroExit) {
  test::TempDir dir;
  const std::string out = (dir.path() / "x.json").string();
  const std::vector<std::vector<std::string>> cases = {
      {"probe", "extraction", "--fields", "teapot", "--res", "32", "--out", out},
      {"probe", "extraction", "--fields", "blob", "--res", "8", "--out", out},
      {"probe", "extraction", "--fields", "blob", "--res", "512", "--out", out},
      {"probe", "extraction", "--fields", "blob", "--res", "32", "--repeats", "0", "--out", out},
      {"probe", "extraction", "--fields", "blob", "--res", "abc", "--out", out},
      {"probe", "extraction", "--fields", "blob", "--res", "32", "--gl", "vulkan", "--out", out},
      {"probe", "extraction", "--fields", "blob", "--res", "32"},
  };
  for (const auto& args : cases) {
    const auto r = runTallow(args);
    std::string joined;
    for (const auto& a : args) joined += a + " ";
    EXPECT_NE(r.exitCode, 0) << joined;
    EXPECT_EQ(test::lineCount(r.err), 1) << joined << "\n" << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace tallow
