// `tallow view` (the ImGui window, under Xvfb), its scripts and saved presets, and capture's
// --script and --video: what a user sees and gets, checked by pixels, stats.json and images.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>

#include "gpu/image_io.h"
#include "gpu/tonemap.h"
#include "support/run_tallow.h"
#include "support/temp_dir.h"
#include "support/xvfb.h"

namespace tallow {
namespace {

using test::runTallow;
using json = nlohmann::json;

// Small and quick on llvmpipe: a 320x240 window, K = 4 maps of 64², N = 2 samples, a 32³ lattice.
const std::vector<std::string> kSmall = {"--size", "320x240", "--set", "sss.map_size=64", "--set",
                                         "sss.light_map_size=64", "--set", "sss.maps=4", "--set", "sss.samples=2",
                                         "--set", "render.shadow_map_size=256", "--set", "field.res=32"};

/// `tallow ARGS… kSmall…` as one shell line, every word single-quoted.
std::string tallowLine(std::vector<std::string> args, bool small = true) {
  if (small) args.insert(args.end(), kSmall.begin(), kSmall.end());
  std::string line = std::string("'") + TALLOW_TEST_BINARY + "'";
  for (const std::string& a : args) {
    line += " '";
    for (char c : a) line += c == '\'' ? std::string("'\\''") : std::string(1, c);
    line += "'";
  }
  return line;
}

json readJson(const std::filesystem::path& file) {
  std::ifstream in(file);
  return json::parse(in);
}

/// 8-bit colour of pixel (x, y) of a PNG read back (readPng returns byte / 255).
glm::ivec3 byteAt(const gpu::Image& png, int x, int y) {
  const glm::vec4 p = png.at(x, y);
  return glm::ivec3(std::lround(p.r * 255.0f), std::lround(p.g * 255.0f), std::lround(p.b * 255.0f));
}

int maxChannelGap(const glm::ivec3& a, const glm::ivec3& b) {
  const glm::ivec3 d = glm::abs(a - b);
  return std::max({d.x, d.y, d.z});
}

#define SKIP_WITHOUT_XVFB() \
  if (!test::xvfbAvailable()) GTEST_SKIP() << "Xvfb is not installed"

TEST(View, ScreenshotShowsTheObjectAndThePanel) {
  SKIP_WITHOUT_XVFB();
  test::TempDir dir;
  const auto r = test::runUnderXvfb(
      tallowLine({"view", "--preset", "blob", "--frames", "30", "--fps", "30", "--screenshot", "out.png"}), dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const gpu::Image png = gpu::readPng(dir.path() / "out.png");
  ASSERT_EQ(png.width, 320);
  ASSERT_EQ(png.height, 240);

  // The panel: ImGui's window at the top left, 40% of the width (128 px). Its title bar has the dark
  // style's TitleBgActive colour, (0.16, 0.29, 0.48) in imgui_draw.cpp's StyleColorsDark, i.e.
  // (41, 74, 122) in bytes; the right half of the bar has no title text. ±2: rounding of the
  // backend's 8-bit vertex colours.
  const glm::ivec3 titleBar(41, 74, 122);
  int titlePixels = 0;
  for (int x = 70; x < 120; ++x) titlePixels += maxChannelGap(byteAt(png, x, 8), titleBar) <= 2;
  EXPECT_GE(titlePixels, 45) << "of 50 pixels of the title bar, at (70..119, 8): " << byteAt(png, 100, 8).x << ","
                             << byteAt(png, 100, 8).y << "," << byteAt(png, 100, 8).z;
  // Its text: white glyphs (ImGuiCol_Text is (1, 1, 1)); the image left of x = 128 is dark sky and
  // grey floor, which never reaches 250 in every channel.
  int white = 0;
  for (int y = 20; y < 240; ++y)
    for (int x = 0; x < 128; ++x) {
      const glm::ivec3 c = byteAt(png, x, y);
      white += c.x >= 250 && c.y >= 250 && c.z >= 250;
    }
  EXPECT_GT(white, 100) << "no text in the panel";

  // The image: the sky at the top right is the preset's background radiance (0.03, 0.03, 0.035)
  // through the ACES tone map at 0 EV (±1: rounding); the blob at the image centre is not sky.
  gpu::ToneMapSettings aces;
  const glm::vec3 sky = gpu::toneMapToSrgb(glm::vec3(0.03f, 0.03f, 0.035f), aces);
  const glm::ivec3 skyByte(std::lround(sky.r * 255), std::lround(sky.g * 255), std::lround(sky.b * 255));
  EXPECT_LE(maxChannelGap(byteAt(png, 315, 4), skyByte), 1);
  double gap = 0.0;
  int n = 0;
  for (int y = 100; y < 140; ++y)
    for (int x = 150; x < 190; ++x, ++n) gap += maxChannelGap(byteAt(png, x, y), skyByte);
  EXPECT_GT(gap / n, 40.0) << "the centre of the image looks like the sky: no object";
}

TEST(View, ScriptChangesTakeEffectOnTheNextFrame) {
  SKIP_WITHOUT_XVFB();
  test::TempDir dir;
  dir.write("s.txt",
            "frame 3 set sss.maps=2\n"
            "frame 5 set sss.samples=1\n"
            "frame 7 set method=albedo\n"
            "frame 8 orbit 90 0\n");
  const auto r = test::runUnderXvfb(tallowLine({"view", "--preset", "blob", "--paused", "--fps", "30", "--frames", "9",
                                                "--script", "s.txt", "--stats", "stats.json"}),
                                    dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const json frames = readJson(dir.path() / "stats.json")["frames"];
  ASSERT_EQ(frames.size(), 9u);
  // The paused blob stands still, so the maps accumulate frame after frame until a change restarts
  // them; each change is listed on the frame it took effect, which shows it.
  const int accumulated[] = {1, 2, 3, 1, 2, 1, 2};
  const int k[] = {4, 4, 4, 2, 2, 2, 2};
  for (int i = 0; i < 7; ++i) {
    EXPECT_EQ(frames[i]["sss"]["frames_accumulated"], accumulated[i]) << "frame " << i;
    EXPECT_EQ(frames[i]["sss"]["maps"], k[i]) << "frame " << i;
    EXPECT_TRUE(frames[i]["gpu_ms"].contains("sss.maps")) << "frame " << i;
  }
  EXPECT_EQ(frames[3]["changed"], json({{"sss.maps", 2}}));
  EXPECT_EQ(frames[5]["changed"], json({{"sss.samples", 1}}));
  EXPECT_EQ(frames[7]["changed"], json({{"method", "albedo"}}));
  EXPECT_FALSE(frames[7]["gpu_ms"].contains("sss.maps")) << "method albedo runs no maps";
  for (int i : {0, 1, 2, 4, 6}) EXPECT_EQ(frames[i]["changed"], json::object()) << "frame " << i;
  // Orbit by 90° about +y of the camera (0, 0.1, 0.32) around its target (0, 0.05, 0): (0.32, 0.1, 0).
  const json position = frames[8]["changed"]["camera.position"];
  ASSERT_TRUE(position.is_array()) << frames[8]["changed"];
  EXPECT_NEAR(position[0].get<double>(), 0.32, 1e-6);
  EXPECT_NEAR(position[1].get<double>(), 0.1, 1e-6);
  EXPECT_NEAR(position[2].get<double>(), 0.0, 1e-6);
}

TEST(View, SavedPresetCapturesToTheWindowsRadiance) {
  SKIP_WITHOUT_XVFB();
  test::TempDir dir;
  dir.write("s.txt",
            "frame 0 orbit 40 15\n"
            "frame 0 zoom 1.2\n"
            "frame 0 set material=Marble\n"
            "frame 0 set material.eta=1.4\n"
            "frame 0 set light.intensity=3,2,1\n"
            "frame 0 set render.exposure_ev=1\n");
  const auto r = test::runUnderXvfb(tallowLine({"view", "--preset", "blob", "--fps", "30", "--time", "2.5", "--frames",
                                                "1", "--script", "s.txt", "--screenshot", "window.exr",
                                                "--save-preset", "saved.json"}),
                                    dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const auto c = runTallow({"capture", "--preset", (dir.path() / "saved.json").string(), "--out",
                            (dir.path() / "c").string()});
  ASSERT_EQ(c.exitCode, 0) << c.err;
  const gpu::Image window = gpu::readExr(dir.path() / "window.exr");
  const gpu::Image capture = gpu::readExr(dir.path() / "c" / "frame_0000.exr");
  ASSERT_EQ(window.width, capture.width);
  ASSERT_EQ(window.height, capture.height);
  // The same Mesa llvmpipe renders both (through GLX in the window, OSMesa in capture) from the same
  // parameters, time and seeds, so the images agree to the storage: both are half floats, whose
  // rounding step is 2^-11 relative; allow one step either way (2^-10) per channel.
  double worst = 0.0;
  for (std::size_t i = 0; i < window.pixels.size(); ++i)
    for (int ch = 0; ch < 3; ++ch) {
      const double a = window.pixels[i][ch], b = capture.pixels[i][ch];
      worst = std::max(worst, std::abs(a - b) / std::max({std::abs(a), std::abs(b), 1e-4}));
    }
  std::printf("[ view    ] saved preset: largest |window - capture| / value %.3g (of %zu pixels)\n", worst,
              window.pixels.size());
  EXPECT_LE(worst, std::ldexp(1.0, -10));
}

/// The failure contract of the commands: non-zero exit, one line starting "tallow: " containing
/// `expected`, and no file left in `dir` beyond `inputs` it already held.
void expectCleanFailure(const test::CommandResult& r, const std::string& expected, const test::TempDir& dir,
                        const std::vector<std::string>& inputs) {
  EXPECT_NE(r.exitCode, 0);
  EXPECT_EQ(test::lineCount(r.err), 1) << r.err;
  EXPECT_EQ(r.err.rfind("tallow: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(expected), std::string::npos) << "stderr: " << r.err << "expected: " << expected;
  EXPECT_EQ(dir.entries(), inputs) << "files were written";
}

TEST(View, BadInputsFailWithOneLineBeforeAWindowOpens) {
  test::TempDir dir;
  const auto script = dir.write("bad.txt", "frame 0 pause\nframe 1 set sss.maps=0\n");
  const auto notExr = dir.write("ref.exr", "not an image");
  const auto p = [&](const char* name) { return (dir.path() / name).string(); };
  const std::vector<std::string> inputs = {"bad.txt", "ref.exr"};
  // No display: the inputs are checked first, so the message is the same with or without one.
  const std::vector<std::string> noDisplay = {"DISPLAY=", "WAYLAND_DISPLAY="};
  expectCleanFailure(runTallow({"view", "--script", script.string()}, noDisplay),
                     script.string() + ":2:22: sss.maps: 0 is out of range [1, 256]", dir, inputs);
  expectCleanFailure(runTallow({"view", "--reference", notExr.string()}, noDisplay), "--reference: " + notExr.string(),
                     dir, inputs);
  expectCleanFailure(runTallow({"view", "--screenshot", p("a.jpg")}, noDisplay),
                     "--screenshot: expected a .png or .exr file", dir, inputs);
  expectCleanFailure(runTallow({"view", "--debug-view", "mpa"}, noDisplay), "--debug-view: unknown debug view \"mpa\"",
                     dir, inputs);
  expectCleanFailure(runTallow({"view", "--size", "64x36", "--screenshot", p("a.png")}, noDisplay),
                     "no display: --screenshot needs the window", dir, inputs);
  // A reference of another size than the image.
  gpu::writeExr(dir.path() / "small.exr", gpu::Image(8, 8), gpu::ExrPixelType::Half);
  expectCleanFailure(runTallow({"view", "--size", "64x36", "--reference", p("small.exr")}, noDisplay),
                     "--reference: " + p("small.exr") + " is 8x8, the image 64x36 (give --size 8x8)", dir,
                     {"bad.txt", "ref.exr", "small.exr"});
  // Capture's script runs no window commands; its frames must exist.
  dir.write("shot.txt", "frame 0 screenshot a.png\n");
  dir.write("late.txt", "frame 3 pause\n");
  const std::vector<std::string> more = {"bad.txt", "late.txt", "ref.exr", "shot.txt", "small.exr"};
  expectCleanFailure(runTallow({"capture", "--script", p("shot.txt"), "--out", p("o")}),
                     p("shot.txt") + ":1:9: screenshot applies to view only", dir, more);
  expectCleanFailure(runTallow({"capture", "--script", p("late.txt"), "--frames", "2", "--out", p("o")}),
                     p("late.txt") + ":1:9: frame 3 is beyond --frames 2", dir, more);
  expectCleanFailure(runTallow({"capture", "--video", p("v.avi"), "--out", p("o")}),
                     "--video: " + p("v.avi") + ": unknown video container", dir, more);
  expectCleanFailure(runTallow({"capture", "--video", p("v.mp4"), "--out", p("o")}, {"TALLOW_FFMPEG=/nonexistent"}),
                     "--video: ffmpeg is not installed", dir, more);
}

TEST(Capture, ScriptChangesAreRecordedPerFrame) {
  test::TempDir dir;
  dir.write("s.txt", "frame 1 pause\nframe 2 set sss.maps=2\nframe 3 seek 1.5\n");
  const auto r = runTallow({"capture", "--preset", "blob", "--frames", "4", "--fps", "10", "--script",
                            (dir.path() / "s.txt").string(), "--out", (dir.path() / "o").string(), "--size", "96x64",
                            "--set", "sss.map_size=32", "--set", "sss.maps=4", "--set", "field.res=24"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const json frames = readJson(dir.path() / "o" / "stats.json")["frames"];
  ASSERT_EQ(frames.size(), 4u);
  // Frame i at i / fps until the pause at frame 1 holds the clock at 0.1 s; the seek puts frame 3 at 1.5 s.
  const double times[] = {0.0, 0.1, 0.1, 1.5};
  for (int i = 0; i < 4; ++i) EXPECT_DOUBLE_EQ(frames[i]["time_s"].get<double>(), times[i]) << i;
  // Frames 1 and 2 show the same instant: the maps accumulate there, until the change of K restarts them.
  EXPECT_EQ(frames[1]["sss"]["frames_accumulated"], 1);
  EXPECT_EQ(frames[2]["changed"], json({{"sss.maps", 2}}));
  EXPECT_EQ(frames[2]["sss"]["maps"], 2);
  EXPECT_EQ(frames[2]["sss"]["frames_accumulated"], 1);
  EXPECT_EQ(frames[1]["sss"]["maps"], 4);
}

TEST(Capture, VideoHoldsTheFrames) {
  if (std::system("command -v ffmpeg >/dev/null 2>&1 && command -v ffprobe >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "ffmpeg is not installed";
  test::TempDir dir;
  const auto out = dir.path() / "o";
  const auto video = dir.path() / "v.mp4";
  const auto r = runTallow({"capture", "--preset", "blob", "--frames", "6", "--fps", "12", "--size", "96x63", "--set",
                            "sss.map_size=32", "--set", "sss.maps=4", "--set", "field.res=24", "--out", out.string(),
                            "--video", video.string()});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  // ffprobe (not our code) reads the stream back: six frames, the odd height padded to even.
  const std::string probe = "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
                            "stream=nb_read_frames,width,height,r_frame_rate -of json '" + video.string() + "' > '" +
                            (dir.path() / "probe.json").string() + "'";
  ASSERT_EQ(std::system(probe.c_str()), 0);
  const json stream = readJson(dir.path() / "probe.json")["streams"][0];
  EXPECT_EQ(stream["nb_read_frames"], "6");
  EXPECT_EQ(stream["width"], 96);
  EXPECT_EQ(stream["height"], 64);
  EXPECT_EQ(stream["r_frame_rate"], "12/1");
  // Its first frame decoded is the first PNG frame, up to H.264 at CRF 18 in 4:2:0: chroma at half
  // resolution blurs colour edges. Measured: a mean of 0.65 levels of 255, 34 at worst (an edge of
  // the blob's per-band noise); allowed: a mean of 2 levels and a quarter of the range at one pixel,
  // which a wrong frame, order, size or tone map exceeds many times.
  const std::string decode = "ffmpeg -v error -i '" + video.string() + "' -frames:v 1 -vf format=rgb24,crop=96:63:0:0 '" +
                             (dir.path() / "first.png").string() + "'";
  ASSERT_EQ(std::system(decode.c_str()), 0);
  const gpu::Image decoded = gpu::readPng(dir.path() / "first.png");
  const gpu::Image frame = gpu::readPng(out / "frame_0000.png");
  ASSERT_EQ(decoded.width, frame.width);
  ASSERT_EQ(decoded.height, frame.height);
  double sum = 0.0, worst = 0.0;
  for (std::size_t i = 0; i < frame.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double d = std::abs(decoded.pixels[i][c] - frame.pixels[i][c]) * 255.0;
      sum += d;
      worst = std::max(worst, d);
    }
  const double mean = sum / (3.0 * static_cast<double>(frame.pixels.size()));
  std::printf("[ video   ] first frame decoded against the PNG: mean |difference| %.2f levels, largest %.0f\n", mean,
              worst);
  EXPECT_LE(mean, 2.0);
  EXPECT_LE(worst, 64.0);
}

}  // namespace
}  // namespace tallow
