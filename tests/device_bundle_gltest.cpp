// The device bundle end to end (issue 18, docs/device-bench.md): scripts/device_bundle.sh packs this
// build's binaries, the archive is unpacked into a temporary folder outside the checkout, and its
// bench.sh runs in --quick mode from an emptied environment (`env -i`, no TALLOW_* set) on llvmpipe
// through EGL; both reports are read back and checked against what the rows must show. Also: the
// scripts' argument errors, and dual contouring through EGL (which the bench renders with) against
// OSMesa.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include <glad/gl.h>

#include "app/bench_report/gather_flops.h"
#include "gpu/gl_context.h"
#include "sss/bssrdf/material.h"
#include "support/run_tallow.h"
#include "support/temp_dir.h"

namespace tallow {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

/// Runs `command` through /bin/sh in `cwd`, stdout and stderr captured apart.
test::CommandResult shell(const std::string& command, const fs::path& cwd) {
  test::TempDir io;
  const std::string full = "cd " + quote(cwd.string()) + " && " + command + " >" + quote((io.path() / "out").string()) +
                           " 2>" + quote((io.path() / "err").string());
  const int status = std::system(full.c_str());
  test::CommandResult r;
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(io.path() / "out");
  r.err = slurp(io.path() / "err");
  return r;
}

const fs::path kSource = TALLOW_TEST_SOURCE_DIR;
const fs::path kBuild = fs::path(TALLOW_TEST_BINARY).parent_path();
/// Issue 18's budget for the archive.
constexpr std::uintmax_t kMaxBundleBytes = 60u << 20;

std::string fixed2(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", x);
  return buf;
}

TEST(DeviceBundle, QuickBenchFromAnEmptiedEnvironmentWritesBothReports) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "the bundle is a Release artefact; device_bundle.sh refuses sanitizer builds";
#endif
  test::TempDir tmp;
  // xz level 1: the same files as the default level's archive, a fifth of the compression time.
  const auto built = shell("bash " + quote((kSource / "scripts/device_bundle.sh").string()) + " --build-dir " +
                               quote(kBuild.string()) + " --xz-level 1 " + quote((tmp.path() / "bundle").string()),
                           tmp.path());
  ASSERT_EQ(built.exitCode, 0) << built.err;
  const fs::path archive = tmp.path() / "bundle/tallow-device.tar.xz";
  ASSERT_TRUE(fs::exists(archive));
  EXPECT_LE(fs::file_size(archive), kMaxBundleBytes);
  EXPECT_NE(built.out.find("MiB"), std::string::npos) << built.out;

  const auto listing = shell("tar -tJf " + quote(archive.string()), tmp.path());
  ASSERT_EQ(listing.exitCode, 0) << listing.err;
  for (const char* entry : {"tallow-device/bench.sh", "tallow-device/bin/tallow", "tallow-device/bin/tallow_bench_report",
                            "tallow-device/lib/libopenvdb.so.10.0", "tallow-device/lib/libembree3.so.3",
                            "tallow-device/lib/base/libstdc++.so.6", "tallow-device/data/materials.csv",
                            "tallow-device/data/bunny.ply", "tallow-device/presets/candle.json", "tallow-device/bundle.json"})
    EXPECT_NE(listing.out.find(std::string(entry) + "\n"), std::string::npos) << entry;
  // Mesa's software stack stays out (loaded with dlopen only for --gl osmesa), and so do the
  // machine's own glibc and GL loaders.
  for (const char* absent : {"libOSMesa", "libLLVM", "libEGL", "libGLdispatch", "/libc.so", "ld-linux"})
    EXPECT_EQ(listing.out.find(absent), std::string::npos) << absent;

  const fs::path unpacked = tmp.path() / "elsewhere";
  fs::create_directories(unpacked);
  ASSERT_EQ(shell("tar -xJf " + quote(archive.string()) + " -C " + quote(unpacked.string()), tmp.path()).exitCode, 0);
  const json bundle = json::parse(slurp(unpacked / "tallow-device/bundle.json"));
  EXPECT_EQ(bundle["commit"].get<std::string>().size(), 40u);
  EXPECT_TRUE(std::regex_match(bundle["glibc_needed"].get<std::string>(), std::regex("GLIBC_2\\.[0-9]+")));

  const fs::path out = tmp.path() / "results";
  const auto bench = shell("env -i " + quote((unpacked / "tallow-device/bench.sh").string()) + " --quick --out " +
                               quote(out.string()),
                           tmp.path());
  ASSERT_EQ(bench.exitCode, 0) << bench.out << bench.err;
  EXPECT_NE(bench.out.find("[11/11"), std::string::npos) << "progress is printed row by row:\n" << bench.out;
  ASSERT_TRUE(fs::exists(out / "results.json"));
  ASSERT_TRUE(fs::exists(out / "results.md"));
  const json r = json::parse(slurp(out / "results.json"));

  // The device: llvmpipe through EGL, and said to be software.
  EXPECT_NE(r["device"]["GL_RENDERER"].get<std::string>().find("llvmpipe"), std::string::npos);
  EXPECT_EQ(r["device"]["backend"], "egl");
  EXPECT_TRUE(r["device"]["software"].get<bool>());
  // The limits that decide the passes' paths are logged (issue 39, point 6).
  ASSERT_TRUE(r["device"].contains("gl_limits"));
  EXPECT_TRUE(r["device"]["gl_limits"].contains("GL_MAX_GEOMETRY_OUTPUT_VERTICES")) << r["device"].dump();
  EXPECT_EQ(r["meta"]["mode"], "quick");

  // Every row ran and was read.
  const std::set<std::string> expected = {"preflight", "candle_animated", "candle_converged", "gather_fragment",
                                          "gather_compute", "dc_32", "dc_32_geometry", "occupancy_radiosity-maps_35",
                                          "occupancy_radiosity-maps_17", "occupancy_no-cache_35", "occupancy_no-cache_17"};
  std::set<std::string> names;
  for (const json& row : r["rows"]) {
    names.insert(row["name"]);
    EXPECT_EQ(row["status"], "ok") << row.dump();
    ASSERT_TRUE(row.contains("metrics")) << row.dump();
    if (row["kind"] == "capture") {
      EXPECT_GT(row["metrics"]["gpu_memory_bytes"].get<double>(), 0.0) << row["name"];
    }
    // bench.sh turns GL error reports on (TALLOW_GL_ERRORS): a draw the driver refuses shows here.
    EXPECT_EQ(row["gl_errors"], 0) << row.dump();
  }
  EXPECT_EQ(names, expected);
  EXPECT_EQ(r["rows_ok"], expected.size());

  // The candle: converged frames only run the camera's passes; animated ones rebuild the field
  // on the CPU and restart the maps, so they must be slower.
  const json& candle = r["figures"]["candle"];
  ASSERT_TRUE(candle["animated_fps"].is_number());
  ASSERT_TRUE(candle["converged_fps"].is_number());
  EXPECT_GT(candle["animated_fps"].get<double>(), 0.0);
  EXPECT_GT(candle["converged_fps"].get<double>(), candle["animated_fps"].get<double>());

  // The gather: both passes timed, the FLOPs those of the shared lines for the bunny's marble.
  const json& gather = r["figures"]["gather"];
  const auto marble = sss::MaterialTable::load(fs::path(TALLOW_TEST_DATA_DIR) / "materials.csv").find("Marble");
  ASSERT_TRUE(marble.has_value());
  EXPECT_DOUBLE_EQ(gather["flops_per_sample"].get<double>(),
                   flops::countGatherFlops(*marble, sss::BssrdfModel::Directional, 8).directional.flopsMean);
  for (const char* pass : {"fragment", "compute"}) {
    ASSERT_TRUE(gather["runs"].contains(pass)) << pass;
    EXPECT_GT(gather["runs"][pass]["evaluations_per_s"].get<double>(), 0.0);
    EXPECT_DOUBLE_EQ(gather["runs"][pass]["flops_per_s"].get<double>(),
                     gather["runs"][pass]["evaluations_per_s"].get<double>() * gather["flops_per_sample"].get<double>());
  }

  // Dual contouring through EGL extracted a surface by both paths: 31³ cells, a candle's worth of
  // triangles, the same count each way.
  ASSERT_EQ(r["figures"]["dual_contouring"].size(), 2u);
  std::set<std::string> extractions;
  for (const json& dc : r["figures"]["dual_contouring"]) {
    extractions.insert(dc["extraction"].get<std::string>());
    EXPECT_EQ(dc["res"], 32);
    EXPECT_DOUBLE_EQ(dc["cells"].get<double>(), 31.0 * 31.0 * 31.0);
    EXPECT_GT(dc["triangles"].get<double>(), 500.0);
    EXPECT_GT(dc["cells_per_s"].get<double>(), 0.0);
    EXPECT_EQ(dc["triangles"], r["figures"]["dual_contouring"][0]["triangles"]);
  }
  EXPECT_EQ(extractions, (std::set<std::string>{"compute", "geometry"}));

  // Occupancy: a narrower field of view makes the blob cover more of the screen, for both methods.
  for (const char* method : {"radiosity-maps", "no-cache"}) {
    const json& runs = r["figures"]["occupancy"]["runs"][method];
    ASSERT_EQ(runs.size(), 2u) << method;
    const json& wide = runs[0]["fov_deg"].get<double>() > runs[1]["fov_deg"].get<double>() ? runs[0] : runs[1];
    const json& narrow = &wide == &runs[0] ? runs[1] : runs[0];
    EXPECT_GT(wide["occupancy"].get<double>(), 0.0) << method;
    EXPECT_GT(narrow["occupancy"].get<double>(), wide["occupancy"].get<double>()) << method;
  }
  EXPECT_TRUE(r["figures"]["occupancy"]["crossover"].is_number() || r["figures"]["occupancy"]["crossover"].is_null());

  // results.md is made from results.json: its figures, rows and warning.
  const std::string md = slurp(out / "results.md");
  EXPECT_EQ(md.rfind("# Tallow device bench\n", 0), 0u);
  EXPECT_NE(md.find(r["device"]["GL_RENDERER"].get<std::string>()), std::string::npos);
  EXPECT_NE(md.find("A software renderer"), std::string::npos);
  EXPECT_NE(md.find("**" + fixed2(candle["animated_fps"].get<double>()) + " fps animated**"), std::string::npos) << md;
  EXPECT_NE(md.find("**" + fixed2(candle["converged_fps"].get<double>()) + " fps converged**"), std::string::npos) << md;
  for (const std::string& name : expected) EXPECT_NE(md.find("| " + name + " | ok |"), std::string::npos) << name;
  // Whole files only: no temporary file left beside them.
  for (const auto& e : fs::directory_iterator(out)) EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos);
}

TEST(DeviceBundle, ScriptsRefuseBadArgumentsWithOneLine) {
  test::TempDir tmp;
  const std::string bench = "bash " + quote((kSource / "scripts/device_bench.sh").string());
  for (const std::string& args : {std::string("--sizes huge --out x"), std::string("--budget 0 --out x"),
                                  std::string("--quick"), std::string("--out x --frobnicate")}) {
    const auto r = shell(bench + " " + args, tmp.path());
    EXPECT_EQ(r.exitCode, 2) << args;
    EXPECT_EQ(test::lineCount(r.err), 1) << args << ": " << r.err;
    EXPECT_EQ(r.err.rfind("bench.sh: ", 0), 0u) << r.err;
  }
  EXPECT_FALSE(fs::exists(tmp.path() / "x")) << "nothing is created before the arguments are checked";
  const auto r = shell("bash " + quote((kSource / "scripts/device_bundle.sh").string()) + " --build-dir " +
                           quote(tmp.path().string()) + " out",
                       tmp.path());
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_EQ(test::lineCount(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("not a CMake build folder"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(tmp.path() / "out"));
}

/// bench.sh counts the OpenGL errors in each row's log: TALLOW_GL_ERRORS=1 must print them in a
/// Release build. A draw with no framebuffer in a surfaceless EGL context is the error it first
/// caught (below).
TEST(DeviceBundle, GlErrorsAreReportedWhenAskedFor) {
  ASSERT_EQ(setenv("TALLOW_GL_ERRORS", "1", 1), 0);
  gpu::ContextOptions options;
  options.backend = gpu::GlBackend::Egl;
  options.debugOutput = false;  // as in Release: only the variable turns the reports on
  const auto context = gpu::GlContext::create(options);
  unsetenv("TALLOW_GL_ERRORS");
  GLuint vao = 0;
  glCreateVertexArrays(1, &vao);
  glBindVertexArray(vao);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  testing::internal::CaptureStderr();
  glDrawArrays(GL_POINTS, 0, 1);  // no default framebuffer: GL_INVALID_FRAMEBUFFER_OPERATION
  glFinish();
  const std::string err = testing::internal::GetCapturedStderr();
  glBindVertexArray(0);
  glDeleteVertexArrays(1, &vao);
  EXPECT_EQ(err.rfind("gl error ", 0), 0u) << err;
}

/// The bench renders through EGL, whose surfaceless contexts have no default framebuffer: dual
/// contouring's transform-feedback draws once failed there and extracted nothing.
TEST(DeviceBundle, EglExtractsTheSameSurfaceAsOsMesa) {
  test::TempDir tmp;
  std::string counts[2];
  int i = 0;
  for (const char* gl : {"osmesa", "egl"}) {
    const auto r = test::runTallow({"mesh", "--preset", "blob", "--time", "2", "--res", "32", "--gl", gl, "--out",
                                    (tmp.path() / (std::string(gl) + ".ply")).string()});
    ASSERT_EQ(r.exitCode, 0) << gl << ": " << r.err;
    const std::string ply = slurp(tmp.path() / (std::string(gl) + ".ply"));
    std::smatch m;
    ASSERT_TRUE(std::regex_search(ply, m, std::regex("element face ([0-9]+)"))) << gl;
    counts[i++] = m[1];
  }
  EXPECT_GT(std::stoi(counts[0]), 500);
  EXPECT_EQ(counts[0], counts[1]);
}

}  // namespace
}  // namespace tallow
