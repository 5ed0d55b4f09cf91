// The command-line contract, exercised through the real executable: outputs of `tallow capture`,
// agreement of the OSMesa and EGL backends, and one clear line + non-zero exit + no files for each
// kind of bad input.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <unistd.h>

#include <cmath>
#include <fstream>

#include "app/config/params.h"
#include "gpu/image_io.h"
#include "support/failure_contract.h"
#include "support/run_tallow.h"
#include "support/temp_dir.h"
#include "support/xvfb.h"

namespace tallow {
namespace {

using test::expectCleanFailure;
using test::fileCount;
using test::runTallow;

TEST(Cli, CaptureOfABunnyWritesPngExrAndStats) {
  test::TempDir dir;
  const auto out = dir.path() / "capture";
  const auto r = runTallow({"capture", "--preset", "bunny", "--out", out.string(), "--size", "320x180"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  ASSERT_TRUE(std::filesystem::exists(out / "frame_0000.png"));
  ASSERT_TRUE(std::filesystem::exists(out / "frame_0000.exr"));
  ASSERT_TRUE(std::filesystem::exists(out / "stats.json"));
  EXPECT_EQ(fileCount(out), 3);  // no temporary files left behind

  const gpu::Image exr = gpu::readExr(out / "frame_0000.exr");
  ASSERT_EQ(exr.width, 320);
  ASSERT_EQ(exr.height, 180);
  float maxValue = 0.0f;
  for (const auto& p : exr.pixels)
    for (int c = 0; c < 4; ++c) {
      ASSERT_TRUE(std::isfinite(p[c]));
      maxValue = std::max(maxValue, p[c]);
    }
  EXPECT_GT(maxValue, 0.0f);

  std::ifstream in(out / "stats.json");
  const auto stats = nlohmann::json::parse(in);
  EXPECT_FALSE(stats["gl"]["GL_RENDERER"].get<std::string>().empty());
  EXPECT_FALSE(stats["gl"]["GL_VERSION"].get<std::string>().empty());
  // The limits that pick a pass's path (issue 39): GL 4.5 guarantees at least 256 geometry-shader
  // output vertices and 4 transform-feedback buffers.
  EXPECT_GE(stats["gl"]["limits"]["GL_MAX_GEOMETRY_OUTPUT_VERTICES"].get<int>(), 256);
  EXPECT_GE(stats["gl"]["limits"]["GL_MAX_TRANSFORM_FEEDBACK_BUFFERS"].get<int>(), 4);
  EXPECT_TRUE(stats["gl"]["limits"]["GL_ARB_shader_viewport_layer_array"].is_boolean());
  EXPECT_EQ(stats["resolution"], nlohmann::json({320, 180}));
  EXPECT_EQ(stats["triangles"].get<long>(), 69451 + 2);  // the bunny and the ground's two triangles
  ASSERT_EQ(stats["frames"].size(), 1u);
  EXPECT_GT(stats["frames"][0]["wall_ms"].get<double>(), 0.0);
  EXPECT_TRUE(stats["frames"][0]["gpu_ms"].contains("surface"));
  EXPECT_TRUE(stats["frames"][0]["gpu_ms"].contains("shadow.directional"));
  if (stats["gl"]["limits"]["GL_ARB_pipeline_statistics_query"].get<bool>()) {
    // The camera pass shades each of the 320x180 pixels at least once (the floor covers the view).
    const auto& surface = stats["frames"][0]["invocations"]["surface"];
    EXPECT_GE(surface["fragment"].get<long>(), 320L * 180L);
    EXPECT_GT(surface["vertex"].get<long>(), 69451L);  // the bunny's vertices, at least once each
  }
  EXPECT_FALSE(stats["frames"][0]["gpu_ms"].contains("shadow.point")) << "no point light: no cube shadow pass";
  // Every registry parameter is recorded, with the values in force.
  const auto materials = sss::MaterialTable::load(std::filesystem::path(TALLOW_TEST_DATA_DIR) / "materials.csv");
  const app::Registry registry = app::parameterRegistry(materials);
  for (const auto& p : registry.params())
    EXPECT_TRUE(stats["parameters"].contains(p.key)) << p.key;
  EXPECT_EQ(stats["parameters"]["render.width"], 320);
  EXPECT_EQ(stats["parameters"]["material"], "Marble");
}

TEST(Cli, OsMesaAndEglAgreeWithinOneLevel) {
  test::TempDir dir;
  const auto a = runTallow({"capture", "--preset", "bunny", "--gl", "osmesa", "--size", "320x180", "--out", (dir.path() / "a").string()});
  const auto b = runTallow({"capture", "--preset", "bunny", "--gl", "egl", "--size", "320x180", "--out", (dir.path() / "b").string()});
  ASSERT_EQ(a.exitCode, 0) << a.err;
  ASSERT_EQ(b.exitCode, 0) << b.err;
  const gpu::Image pa = gpu::readPng(dir.path() / "a" / "frame_0000.png");
  const gpu::Image pb = gpu::readPng(dir.path() / "b" / "frame_0000.png");
  ASSERT_EQ(pa.pixels.size(), pb.pixels.size());
  float worst = 0.0f;
  for (std::size_t i = 0; i < pa.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(pa.pixels[i][c] - pb.pixels[i][c]));
  EXPECT_LE(worst, 1.0f / 255.0f + 1e-6f);
}

TEST(Cli, MalformedPresetNamesFileLineAndColumn) {
  test::TempDir dir;
  const auto preset = dir.write("bad.json", "{\n  \"name\": \"x\",\n  \"camera\": {\"type\": \"orthographic\",,}\n}\n");
  const auto out = dir.path() / "out";
  expectCleanFailure(runTallow({"capture", "--preset", preset.string(), "--out", out.string()}),
                     preset.string() + ":3:", out);
}

TEST(Cli, UnknownPresetKeyNamesFileLineAndColumn) {
  test::TempDir dir;
  std::ifstream in(std::string(TALLOW_TEST_SOURCE_DIR) + "/presets/bunny.json");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // Misspell the first "ambient" key: the error must point at it.
  const auto pos = text.find("\"ambient\"");
  ASSERT_NE(pos, std::string::npos);
  text.replace(pos, 9, "\"ambeint\"");
  int line = 1, col = 1;
  for (std::size_t i = 0; i < pos; ++i) {
    if (text[i] == '\n') { ++line; col = 1; } else { ++col; }
  }
  const auto preset = dir.write("typo.json", text);
  const auto out = dir.path() / "out";
  expectCleanFailure(runTallow({"capture", "--preset", preset.string(), "--out", out.string()}),
                     preset.string() + ":" + std::to_string(line) + ":" + std::to_string(col) + ": unknown key \"ambeint\"",
                     out);
}

TEST(Cli, BadSetValuesAreRefused) {
  test::TempDir dir;
  const auto out = dir.path() / "out";
  expectCleanFailure(runTallow({"capture", "--set", "render.shadow_map_size=-4", "--out", out.string()}),
                     "render.shadow_map_size", out);
  expectCleanFailure(runTallow({"capture", "--set", "render.shadw_bias=1", "--out", out.string()}),
                     "render.shadow_bias", out);  // the did-you-mean suggestion
  expectCleanFailure(runTallow({"capture", "--set", "material=Marbel", "--out", out.string()}), "Marble", out);
}

TEST(Cli, MissingMeshFileIsNamed) {
  test::TempDir dir;
  const auto preset = dir.write("nomesh.json", R"({
  "name": "nomesh",
  "camera": {"type": "perspective", "position": [0, 0, 1], "target": [0, 0, 0]},
  "lights": [],
  "objects": [{"name": "ghost", "mesh": "does_not_exist.ply"}]
})");
  const auto out = dir.path() / "out";
  expectCleanFailure(runTallow({"capture", "--preset", preset.string(), "--out", out.string()}), "does_not_exist.ply",
                     out);
}

TEST(Cli, BrokenMeshFileIsNamed) {
  test::TempDir dir;
  dir.write("broken.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                          "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                          "0 0 0\n1 0 0\n0 1\n3 0 1 2\n");
  const auto preset = dir.write("broken.json", R"({
  "name": "broken",
  "camera": {"type": "perspective", "position": [0, 0, 1], "target": [0, 0, 0]},
  "lights": [],
  "objects": [{"name": "b", "mesh": "broken.ply"}]
})");
  const auto out = dir.path() / "out";
  expectCleanFailure(runTallow({"capture", "--preset", preset.string(), "--out", out.string()}), "broken.ply:", out);
}

TEST(Cli, UnwritableOutputFolderIsRefusedBeforeRendering) {
  test::TempDir dir;
  const auto file = dir.write("a_file", "x");
  const auto out = file / "sub";  // a folder below a regular file can never be created
  expectCleanFailure(runTallow({"capture", "--out", out.string()}), "is not a folder", out);
}

TEST(Cli, ContextBelowGl45IsOneClearError) {
  // Mesa caps the version it offers when MESA_GL_VERSION_OVERRIDE is set, as an old driver would.
  test::TempDir dir;
  const auto out = dir.path() / "out";
  for (const char* backend : {"osmesa", "egl"}) {
    expectCleanFailure(runTallow({"capture", "--gl", backend, "--out", out.string()}, {"MESA_GL_VERSION_OVERRIDE=3.3"}),
                       "OpenGL 4.5 core is required, but " + std::string(backend), out);
  }
}

TEST(Cli, ShaderCompileErrorNamesFileAndLine) {
  test::TempDir dir;
  const auto shaders = dir.path() / "shaders";
  std::filesystem::copy(std::string(TALLOW_TEST_SOURCE_DIR) + "/shaders", shaders,
                        std::filesystem::copy_options::recursive);
  {
    std::ofstream f(shaders / "surface.frag", std::ios::app);
    f << "\nthis is not glsl;\n";
  }
  std::ifstream in(shaders / "surface.frag");
  int lines = 0;
  for (std::string l; std::getline(in, l);) ++lines;
  const auto out = dir.path() / "out";
  expectCleanFailure(runTallow({"capture", "--shader-dir", shaders.string(), "--out", out.string()}),
                     "shaders/surface.frag:" + std::to_string(lines) + ": ", out);
}

TEST(Cli, ExplainPrintsThePlan) {
  test::TempDir dir;
  const auto r = runTallow({"capture", "--explain", "--size", "64x64", "--set", "render.shadows=false", "--out",
                            (dir.path() / "o").string()});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("pass surface"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("shadow."), std::string::npos) << "shadows are off, yet a shadow pass is planned:\n" << r.out;
}

}  // namespace
}  // namespace tallow

namespace tallow {
namespace {

TEST(Cli, ViewOpensAWindowWhenADisplayExists) {
  if (!test::xvfbAvailable()) GTEST_SKIP() << "Xvfb is not installed";
  test::TempDir dir;
  // The default preset at small settings: opening the window is the point, not the picture.
  const auto r = test::runUnderXvfb(std::string(TALLOW_TEST_BINARY) +
                                        " view --frames 3 --size 320x180 --set sss.maps=4 --set sss.map_size=64"
                                        " --set sss.light_map_size=64 --set render.shadow_map_size=256",
                                    dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(r.output.find("no display"), std::string::npos) << "fell back to capture: " << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "out")) << "a window run must not capture";
}

/// `a` followed by a small, quick blob: 48x32, K = 4 maps of 64², N = 2.
std::vector<std::string> smallBlob(std::vector<std::string> a) {
  const std::vector<std::string> common = {"--preset", "blob", "--size", "48x32", "--set", "sss.maps=4",
                                           "--set", "sss.map_size=64", "--set", "sss.samples=2"};
  a.insert(a.end(), common.begin(), common.end());
  return a;
}

// --accumulate N renders the frame's time N times and writes the last: the same picture as the N-th
// frame of a capture whose clock a script pauses at frame 0 (a second path through the same
// accumulation: Playback's pause), bit for bit, since both render the same frames with the same seeds.
TEST(Cli, AccumulateWritesThePausedSequencesLastFrame) {
  test::TempDir dir;
  const auto accumulated = dir.path() / "accumulated";
  const auto r = runTallow(smallBlob({"capture", "--accumulate", "3", "--out", accumulated.string()}));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto script = dir.path() / "pause.txt";
  std::ofstream(script) << "frame 0 pause\n";
  const auto paused = dir.path() / "paused";
  const auto p = runTallow(smallBlob({"capture", "--frames", "3", "--script", script.string(), "--out", paused.string()}));
  ASSERT_EQ(p.exitCode, 0) << p.err;

  EXPECT_EQ(fileCount(accumulated), 3) << "one frame written";
  const gpu::Image a = gpu::readExr(accumulated / "frame_0000.exr");
  const gpu::Image third = gpu::readExr(paused / "frame_0002.exr");
  const gpu::Image first = gpu::readExr(paused / "frame_0000.exr");
  ASSERT_EQ(a.pixels.size(), third.pixels.size());
  int differsFromFirst = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) ASSERT_EQ(a.pixels[i][c], third.pixels[i][c]) << "pixel " << i;
    differsFromFirst += a.pixels[i] != first.pixels[i] ? 1 : 0;
  }
  EXPECT_GT(differsFromFirst, 0) << "three accumulated renders differ from one";
  std::ifstream in(accumulated / "stats.json");
  const auto stats = nlohmann::json::parse(in);
  EXPECT_EQ(stats["accumulate"], 3);
  ASSERT_EQ(stats["frames"].size(), 1u);
  EXPECT_EQ(stats["frames"][0]["sss"]["frames_accumulated"], 3) << stats["frames"][0]["sss"].dump();
}

TEST(Cli, ACaptureComparedWithItsOwnStoredFrameDiffersByExactlyZero) {
  // Issue 40, point 4: a stored capture is a golden image (no _stderr.exr beside it: every pixel
  // compared), and the same capture against it is exactly 0 (the frame compared as its half-float
  // EXR stores it; 2e-4 before), by capture --reference and by compare --max-rel-rmse 0.
  test::TempDir dir;
  const auto golden = dir.path() / "golden", run = dir.path() / "run";
  ASSERT_EQ(runTallow(smallBlob({"capture", "--out", golden.string()})).exitCode, 0);
  const auto r = runTallow(smallBlob({"capture", "--out", run.string(), "--reference", (golden / "frame_0000.exr").string()}));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  std::ifstream in(run / "stats.json");
  const auto error = nlohmann::json::parse(in)["frames"][0]["reference_error"];
  EXPECT_EQ(error["rel_rmse"], 0.0) << error.dump();
  EXPECT_EQ(error["new_fireflies"], 0);
  EXPECT_EQ(error["pixels"], 48 * 32) << "a plain EXR: every pixel";
  EXPECT_EQ(error["compared"], "all pixels");
  const auto c = runTallow({"compare", (run / "frame_0000.exr").string(), (golden / "frame_0000.exr").string(),
                            "--max-rel-rmse", "0"});
  EXPECT_EQ(c.exitCode, 0) << c.err;
}

TEST(Cli, ParamsWithAPresetShowsItsValues) {
  const auto defaults = runTallow({"params"});
  const auto candle = runTallow({"params", "--preset", "candle"});
  ASSERT_EQ(candle.exitCode, 0) << candle.err;
  const auto line = [](const std::string& text, const std::string& key) {
    const std::size_t at = text.find("\n" + key + " ");
    return at == std::string::npos ? std::string() : text.substr(at + 1, text.find('\n', at + 1) - at - 1);
  };
  // The registry's default is 0 VPLs; the candle's preset asks for 80 (issue 40: params showed 0).
  EXPECT_NE(line(defaults.out, "vpl.count").find(" 0 "), std::string::npos) << line(defaults.out, "vpl.count");
  EXPECT_NE(line(candle.out, "vpl.count").find(" 80 "), std::string::npos) << line(candle.out, "vpl.count");
  EXPECT_NE(candle.out.find("[candle]"), std::string::npos) << "the column names the preset";
}

TEST(Cli, AccumulateOutOfRangeIsRefused) {
  test::TempDir dir;
  const auto out = dir.path() / "out";
  expectCleanFailure(runTallow({"capture", "--preset", "blob", "--accumulate", "0", "--out", out.string()}),
                     "--accumulate: must be between 1 and", out);
}

TEST(Cli, ViewWithoutADisplayCapturesIntoOut) {
  test::TempDir dir;
  const std::string command = "cd " + dir.path().string() + " && env -u DISPLAY -u WAYLAND_DISPLAY " +
                              std::string(TALLOW_TEST_BINARY) + " view --size 64x36 2>err.txt >/dev/null";
  ASSERT_EQ(std::system(command.c_str()), 0);
  std::ifstream err(dir.path() / "err.txt");
  const std::string text((std::istreambuf_iterator<char>(err)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("no display; capturing candle into out/"), std::string::npos) << text;
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "out" / "frame_0000.png"));
  std::ifstream in(dir.path() / "out" / "stats.json");
  const auto stats = nlohmann::json::parse(in);
  EXPECT_EQ(stats["preset"]["name"], "candle");
  EXPECT_TRUE(stats["frames"][0]["gpu_ms"].contains("vpl")) << "the default preset lights the table with VPLs";
  EXPECT_EQ(stats["frames"][0]["time_s"], 16.0) << "the candle's start_s";
  EXPECT_EQ(stats["accumulate"], 16) << "a still frame: the maps accumulate as in a paused window";
  // All 16: the first render of the melting candle's still reuses the maps' history and starts the
  // still's count after it, so one render more is made (issue 40: 15 were recorded).
  EXPECT_EQ(stats["frames"][0]["sss"]["frames_accumulated"], 16) << stats["frames"][0]["sss"].dump();
  // The flame is drawn (issue 16, point 5), and each pass has its CPU time beside its GPU time.
  const auto& frame = stats["frames"][0];
  EXPECT_TRUE(frame["gpu_ms"].contains("flame")) << frame["gpu_ms"].dump();
  EXPECT_TRUE(frame["cpu_ms"].contains("field.sample")) << frame.dump();
  EXPECT_GT(frame["cpu_ms"]["field.sample"].get<double>(), 0.0) << "sampling the field is CPU work";
  // The lit wax reads warm, not clipped white: under 2% of the candle's pixels have all three
  // channels >= 0.98 after the tone map (issue 16's acceptance figure).
  const double translucent = frame["pixels"]["translucent"].get<double>();
  ASSERT_GT(translucent, 50.0) << "the candle is in the picture";
  EXPECT_LT(frame["pixels"]["translucent_clipped"].get<double>() / translucent, 0.02) << frame["pixels"].dump();
}

}  // namespace
}  // namespace tallow
