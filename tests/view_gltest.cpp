// `tallow view` (the ImGui window, under Xvfb), its scripts and saved presets, and capture's
// --script and --video: what a user sees and gets, checked by pixels, stats.json and images.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>

#include "gpu/image_io.h"
#include "gpu/tonemap.h"
#include "support/failure_contract.h"
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

/// A file's text (empty when it cannot be read).
std::string readText(const std::filesystem::path& file) {
  std::ifstream in(file);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
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

TEST(View, ThePictureLiesBesideThePanelPixelForPixel) {
  SKIP_WITHOUT_XVFB();
  test::TempDir dir;
  const auto r = test::runUnderXvfb(tallowLine({"view", "--preset", "blob", "--frames", "20", "--fps", "30", "--paused",
                                                "--screenshot", "out.png", "--screenshot", "out.exr", "--stats",
                                                "stats.json"}),
                                    dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const json stats = readJson(dir.path() / "stats.json");
  const json view = stats["frames"].back()["view"];
  // The window opens with the panel's 420 pixels beside the 320x240 image, as tall as 95% of the
  // 800x600 screen (570: room for the panel's parameters); the image is shown at scale 1, centred
  // in the viewport right of the panel.
  EXPECT_EQ(view["window"], json({740, 570}));
  EXPECT_EQ(view["panel"], json({0, 0, 420, 570}));
  EXPECT_EQ(view["image"], json({420, 165, 320, 240}));
  EXPECT_EQ(view["scale"], 1.0);
  for (const json& frame : stats["frames"]) {
    const json& p = frame["view"]["panel"];
    const json& i = frame["view"]["image"];
    ASSERT_TRUE(p.is_array() && i.is_array());
    EXPECT_LE(p[0].get<int>() + p[2].get<int>(), i[0].get<int>()) << "the panel reaches into the image";
  }
  const gpu::Image png = gpu::readPng(dir.path() / "out.png");
  ASSERT_EQ(png.width, 740);
  ASSERT_EQ(png.height, 570);

  // The image's place in the window shows the rendered image and nothing else: every pixel is the
  // tone-mapped radiance of the same frame (out.exr), up to the EXR's half floats and the GPU's
  // against the CPU's tone map: within 2 levels of 255 nearly everywhere (a panel, a border or a
  // stretched copy over any of it would be off by tens of levels there).
  const gpu::Image exr = gpu::readExr(dir.path() / "out.exr");
  ASSERT_EQ(exr.width, 320);
  gpu::ToneMapSettings toneMap;
  toneMap.op = gpu::parseToneMap(stats["parameters"]["render.tonemap"].get<std::string>());
  toneMap.exposureEv = stats["parameters"]["render.exposure_ev"].get<float>();
  const std::vector<std::uint8_t> expected = gpu::toneMappedRgb8(exr, toneMap);
  int off = 0, worst = 0;
  for (int y = 0; y < 240; ++y)
    for (int x = 0; x < 320; ++x) {
      const std::size_t k = 3 * (static_cast<std::size_t>(y) * 320 + static_cast<std::size_t>(x));
      const glm::ivec3 want(expected[k], expected[k + 1], expected[k + 2]);
      const int gap = maxChannelGap(byteAt(png, 420 + x, 165 + y), want);
      worst = std::max(worst, gap);
      off += gap > 2;
    }
  std::printf("[ view    ] image region against the tone-mapped EXR: %d of 76800 pixels off by more than 2 levels, "
              "largest gap %d\n", off, worst);
  EXPECT_LE(off, 76800 / 200);  // 0.5%
  EXPECT_LE(worst, 16);

  // The panel: ImGui's window at the left, its title bar in the dark style's TitleBgActive colour,
  // (0.16, 0.29, 0.48), i.e. (41, 74, 122) in bytes, right of the title's text; ±2: rounding.
  const glm::ivec3 titleBar(41, 74, 122);
  int titlePixels = 0;
  for (int x = 330; x < 410; ++x) titlePixels += maxChannelGap(byteAt(png, x, 8), titleBar) <= 2;
  EXPECT_GE(titlePixels, 75) << "of 80 pixels of the title bar at (330..409, 8): " << byteAt(png, 380, 8).x << ","
                             << byteAt(png, 380, 8).y << "," << byteAt(png, 380, 8).z;
  // Its text: white glyphs (ImGuiCol_Text is (1, 1, 1)) in the panel.
  int white = 0;
  for (int y = 30; y < 570; ++y)
    for (int x = 0; x < 420; ++x) {
      const glm::ivec3 c = byteAt(png, x, y);
      white += c.x >= 250 && c.y >= 250 && c.z >= 250;
    }
  EXPECT_GT(white, 200) << "no text in the panel";
  // Above and below the image: the window's dark background, not the panel or the picture.
  EXPECT_LE(maxChannelGap(byteAt(png, 580, 60), glm::ivec3(15, 15, 18)), 2);
}

/// The state of every parameter at each frame of a view's stats.json: the first frame's snapshot
/// with each frame's "changed" applied in turn.
std::vector<json> parameterStates(const json& stats) {
  std::vector<json> states;
  json state = stats["parameters"];
  for (const json& frame : stats["frames"]) {
    for (auto it = frame["changed"].begin(); it != frame["changed"].end(); ++it) state[it.key()] = it.value();
    states.push_back(state);
  }
  return states;
}

TEST(View, HotkeysAsScriptEvents) {
  SKIP_WITHOUT_XVFB();
  test::TempDir dir;
  dir.write("keys.txt",
            "frame 2 key space\n"    // pause: the clock holds from frame 2 on
            "frame 4 key right\n"    // one frame on
            "frame 5 key left\n"
            "frame 5 key left\n"     // two back
            "frame 6 orbit 40 0\n"
            "frame 7 key r\n"        // the preset's camera again
            "frame 8 key f1\n"       // the panel hidden: the image fills the window
            "frame 9 key s\n"
            "frame 10 key s\n"       // a second screenshot, numbered after the first
            "frame 11 key f1\n"
            "frame 12 key escape\n"  // quit before frame 12 is drawn
            "frame 13 set sss.maps=2\n");
  const auto r = test::runUnderXvfb(tallowLine({"view", "--preset", "blob", "--fps", "30", "--time", "1", "--frames",
                                                "20", "--script", "keys.txt", "--stats", "stats.json"}),
                                    dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const json frames = readJson(dir.path() / "stats.json")["frames"];
  ASSERT_EQ(frames.size(), 12u) << "Esc at frame 12 closed the window";
  // Times: 1 + i/30 while playing; held once paused; one step on, two back.
  const double step = 1.0 / 30.0;
  const double times[] = {1.0, 1.0 + step, 1.0 + 2 * step, 1.0 + 2 * step, 1.0 + 3 * step, 1.0 + step};
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(frames[i]["time_s"].get<double>(), times[i], 1e-9) << "frame " << i;
  for (int i = 6; i < 12; ++i) EXPECT_NEAR(frames[i]["time_s"].get<double>(), 1.0 + step, 1e-9) << "frame " << i;
  EXPECT_TRUE(frames[1]["view"]["playing"].get<bool>());
  for (int i = 2; i < 12; ++i) EXPECT_FALSE(frames[i]["view"]["playing"].get<bool>()) << "frame " << i;
  // R: the camera back where the orbit took it from.
  const json before = parameterStates(readJson(dir.path() / "stats.json"))[5]["camera.position"];
  ASSERT_TRUE(frames[6]["changed"].contains("camera.position"));
  ASSERT_TRUE(frames[7]["changed"].contains("camera.position"));
  EXPECT_EQ(frames[7]["changed"]["camera.position"], before);
  // F1: no panel, the 320x240 image enlarged 740/320 = 2.3125 times to fill the 740x570 window's
  // width (555 rows), centred.
  for (int i = 8; i < 11; ++i) {
    EXPECT_FALSE(frames[i]["view"]["panel_visible"].get<bool>()) << "frame " << i;
    EXPECT_TRUE(frames[i]["view"]["panel"].is_null());
    EXPECT_EQ(frames[i]["view"]["image"], json({0, 7, 740, 555})) << "frame " << i;
  }
  EXPECT_EQ(frames[11]["view"]["panel"], json({0, 0, 420, 570}));
  // S twice: two numbered files, neither overwriting the other.
  const gpu::Image first = gpu::readPng(dir.path() / "tallow-blob-0001.png");
  const gpu::Image second = gpu::readPng(dir.path() / "tallow-blob-0002.png");
  EXPECT_EQ(first.width, 740);
  EXPECT_EQ(second.height, 570);
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "tallow-blob-0003.png"));
}

TEST(View, KeyTapsAreNotLostAtALowFrameRate) {
#ifndef TALLOW_TEST_XKEYS
  GTEST_SKIP() << "built without Xlib's headers: no tallow_xkeys to press keys";
#else
  SKIP_WITHOUT_XVFB();
  test::TempDir dir;
  // Slow frames (64 samples per texel, 16 maps, the blob moving so the maps restart each frame), and
  // keys tapped as a user does: press and release within a millisecond, inside one frame. Polling
  // the keys' state once a frame sees neither tap; GLFW's key callback queues both. Only the window
  // closing ends the run before its frames, so a lost Esc would run until `timeout` (exit 124, after two minutes).
  // --frames keeps the window in lockstep, one render per window frame (a window left open renders
  // on its own thread: View.AWindowLeftOpenAnswersWhileItRenders).
  const std::string view = "timeout 120 " + tallowLine({"view", "--preset", "blob", "--fps", "30", "--frames", "100000",
                                                         "--stats", "stats.json", "--set", "sss.samples=64", "--set",
                                                         "sss.maps=16"});
  // The first tap once frames are being drawn (the window appears before the first frame).
  const std::string keys = std::string("'") + TALLOW_TEST_XKEYS + "' Tallow 120 wait:3000 space:2500 Escape:0";
  const auto r = test::runUnderXvfb(view + " & pid=$!; " + keys + " || { kill $pid; exit 3; }; wait $pid", dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const json frames = readJson(dir.path() / "stats.json")["frames"];
  ASSERT_GE(frames.size(), 2u);
  std::vector<double> walls;
  for (const json& f : frames) walls.push_back(f["wall_ms"].get<double>());
  std::sort(walls.begin(), walls.end());
  std::printf("[ view    ] %zu frames before Esc, median %.0f ms each\n", frames.size(), walls[walls.size() / 2]);
  EXPECT_FALSE(frames.back()["view"]["playing"].get<bool>()) << "the Space tap paused the clock";
  // Paused once, at one frame: playing before it (unless the first frame outlasted the wait).
  int pauses = 0;
  for (std::size_t i = 1; i < frames.size(); ++i)
    pauses += frames[i - 1]["view"]["playing"].get<bool>() && !frames[i]["view"]["playing"].get<bool>();
  EXPECT_LE(pauses, 1);
#endif
}

TEST(View, AWindowLeftOpenAnswersWhileItRenders) {
  // Issue 40, point 2: a window left open (no --frames, no --script) renders on a thread of its own
  // and keeps drawing the panel and the last picture meanwhile: the paused candle at 160x90 renders
  // in about a second a frame on llvmpipe, the window redraws at least ten times a second. In
  // lockstep every window frame is a render (window_frames = renders), so the ratio tells them apart.
  SKIP_WITHOUT_XVFB();
  test::TempDir dir;
  // SIGTERM after 12 s (timeout(1) sends it twice: to the command and to its group) ends it as a
  // closed terminal does: the frame in flight is finished and recorded, stats.json written whole.
  // With a cold shader cache the first frame alone can outlast the 12 s: one frame, still recorded.
  const auto r = test::runUnderXvfb(
      "timeout --preserve-status -s TERM 12 " +
          tallowLine({"view", "--preset", "candle", "--size", "160x90", "--paused", "--stats", "stats.json"}, false),
      dir.path());
  EXPECT_EQ(r.exitCode, 143) << r.output;
  const json stats = readJson(dir.path() / "stats.json");
  EXPECT_EQ(stats["run"]["state"], "interrupted");
  const json& frames = stats["frames"];
  ASSERT_GE(frames.size(), 1u) << r.output;
  int previousShown = 0;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const json& view = frames[i]["view"];
    EXPECT_TRUE(view["render_thread"].get<bool>()) << "frame " << i;
    EXPECT_FALSE(view["playing"].get<bool>()) << "frame " << i;
    EXPECT_EQ(frames[i]["time_s"], frames[0]["time_s"]) << "paused";
    EXPECT_GE(view["window_frames"].get<int>(), previousShown) << "frame " << i;
    previousShown = view["window_frames"].get<int>();
    // The maps accumulate one frame per render, as in lockstep (no input: no preview), or restart
    // where sss.maps=auto chose another K.
    if (i > 0) {
      const json& sss = frames[i]["sss"];
      const json& before = frames[i - 1]["sss"];
      EXPECT_EQ(sss["frames_accumulated"].get<int>(),
                sss["maps"] == before["maps"] ? std::min(before["frames_accumulated"].get<int>() + 1, 64) : 1)
          << "frame " << i;
    }
  }
  const int windowFrames = frames.back()["view"]["window_frames"].get<int>();
  std::printf("[ view    ] %zu renders, %d window frames in 12 s\n", frames.size(), windowFrames);
  EXPECT_GE(windowFrames, 3 * static_cast<int>(frames.size())) << "the window waited for the renders";
}

TEST(View, ASlowWindowPlaysSlowerInsteadOfSkipping) {
  // Issue 40, point 1: by wall time, frames of seconds on llvmpipe took the candle through its
  // animation in a few frames (0.97 s apart); the clock now moves at most --max-step a frame.
  SKIP_WITHOUT_XVFB();
  test::TempDir dir;
  const auto r = test::runUnderXvfb(tallowLine({"view", "--preset", "candle", "--frames", "4", "--stats", "stats.json",
                                                "--max-step", "0.05"}),
                                    dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const json frames = readJson(dir.path() / "stats.json")["frames"];
  ASSERT_EQ(frames.size(), 4u);
  for (std::size_t i = 1; i < frames.size(); ++i) {
    const double step = frames[i]["time_s"].get<double>() - frames[i - 1]["time_s"].get<double>();
    const double wallS = frames[i - 1]["wall_ms"].get<double>() / 1000.0;
    EXPECT_GT(step, 0.0) << "frame " << i << ": the clock plays";
    EXPECT_LE(step, 0.05 + 1e-9) << "frame " << i;
    // Frames longer than the cap: the panel's "behind real time" share is the step over the frame's time.
    if (wallS > 0.06) {
      EXPECT_LT(frames[i]["view"]["real_time_share"].get<double>(), 1.0) << "frame " << i;
    }
  }
}

TEST(View, AMovingCameraIsAPreviewThatHoldsTheAccumulation) {
  // Issue 40, point 2: while the camera moves the maps keep what they hold instead of accumulating
  // (the default candle at 320x180 on llvmpipe: 0.9 s frames instead of 5.3 s); the first frame
  // without input accumulates again. A scripted orbit is a step of a drag.
  SKIP_WITHOUT_XVFB();
  test::TempDir dir;
  dir.write("orbit.txt", "frame 2 orbit 10 0\nframe 3 orbit 10 0\n");
  const auto r = test::runUnderXvfb(tallowLine({"view", "--preset", "blob", "--paused", "--fps", "30", "--frames", "6",
                                                "--script", "orbit.txt", "--stats", "stats.json"}),
                                    dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const json frames = readJson(dir.path() / "stats.json")["frames"];
  ASSERT_EQ(frames.size(), 6u);
  for (int i = 0; i < 6; ++i) {
    const bool moving = i == 2 || i == 3;
    EXPECT_EQ(frames[i]["view"]["preview"], moving) << "frame " << i;
    EXPECT_EQ(frames[i]["cpu_ms"].contains("sss.maps"), !moving) << "frame " << i;
    EXPECT_TRUE(frames[i]["cpu_ms"].contains("surface")) << "frame " << i << ": the picture is drawn anew";
  }
  const int held = frames[1]["sss"]["frames_accumulated"].get<int>();
  EXPECT_EQ(frames[2]["sss"]["frames_accumulated"], held);
  EXPECT_EQ(frames[3]["sss"]["frames_accumulated"], held);
  EXPECT_EQ(frames[4]["sss"]["frames_accumulated"], held + 1) << "accumulating again once the camera stops";
  EXPECT_TRUE(frames[2]["changed"].contains("camera.position"));
}

TEST(View, ScriptScreenshotsShowTheSceneWhereTheScriptStands) {
  // Issue 40, point 5: a screenshot between two commands of one frame shows the first applied and
  // not the second (it used to be taken after every command of its frame), into a folder made for it.
  SKIP_WITHOUT_XVFB();
  test::TempDir dir;
  dir.write("shots.txt",
            "frame 1 set sss.maps=2\n"
            "frame 1 screenshot shots/k2.exr\n"
            "frame 1 set sss.maps=3\n"
            "frame 1 screenshot shots/deeper/k3.exr\n"
            "frame 2 set sss.maps=5\n");
  const auto r = test::runUnderXvfb(tallowLine({"view", "--preset", "blob", "--fps", "10", "--frames", "4", "--script",
                                                "shots.txt", "--stats", "stats.json"}),
                                    dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const json frames = readJson(dir.path() / "stats.json")["frames"];
  // Frame 1 is drawn twice at the same time: K = 2 for the first screenshot, then K = 3.
  ASSERT_EQ(frames.size(), 5u);
  const int maps[] = {4, 2, 3, 5, 5};
  const int index[] = {0, 1, 1, 2, 3};
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(frames[i]["sss"]["maps"], maps[i]) << "record " << i;
    EXPECT_EQ(frames[i]["index"], index[i]) << "record " << i;
    EXPECT_EQ(frames[i]["view"]["script_step"], i == 2) << "record " << i;
  }
  EXPECT_EQ(frames[2]["time_s"], frames[1]["time_s"]) << "the clock holds for the rest of the frame's script";
  EXPECT_NEAR(frames[3]["time_s"].get<double>(), 0.2, 1e-9);
  // The two pictures differ (K = 2 and K = 3 cover the blob differently), each one whole file.
  const gpu::Image k2 = gpu::readExr(dir.path() / "shots" / "k2.exr");
  const gpu::Image k3 = gpu::readExr(dir.path() / "shots" / "deeper" / "k3.exr");
  ASSERT_EQ(k2.pixels.size(), k3.pixels.size());
  EXPECT_NE(k2.pixels, k3.pixels);
}

TEST(View, ImpossibleDebugViewsEndWithOneLine) {
  // Issue 40, point 5: map:99 of 4 maps showed the final image and exited 0.
  SKIP_WITHOUT_XVFB();
  test::TempDir dir;
  auto r = test::runUnderXvfb(tallowLine({"view", "--preset", "blob", "--frames", "2", "--debug-view", "map:99"}) +
                                  " 2>err.txt",
                              dir.path());
  EXPECT_NE(r.exitCode, 0);
  EXPECT_EQ(readText(dir.path() / "err.txt"), "tallow: --debug-view map:99: map 99 does not exist (K = 4)\n");
  dir.write("debug.txt", "frame 1 debug map:2\nframe 2 debug map:7\n");
  r = test::runUnderXvfb(tallowLine({"view", "--preset", "blob", "--frames", "4", "--script", "debug.txt", "--stats",
                                     "stats.json"}) +
                             " 2>err2.txt",
                         dir.path());
  EXPECT_NE(r.exitCode, 0);
  EXPECT_EQ(readText(dir.path() / "err2.txt"), "tallow: debug.txt:2:9: debug: map 7 does not exist (K = 4)\n");
  // --stats written whole, saying where the run stopped and why, with the two frames drawn before.
  const json stats = readJson(dir.path() / "stats.json");
  EXPECT_EQ(stats["run"]["state"], "failed");
  EXPECT_EQ(stats["run"]["stop_reason"], "debug.txt:2:9: debug: map 7 does not exist (K = 4)");
  EXPECT_EQ(stats["frames"].size(), 2u);
}

TEST(View, UndoRestoresTheExactPresetAndRedoReappliesTheEdit) {
  SKIP_WITHOUT_XVFB();
  test::TempDir dir;
  dir.write("edits.txt",
            "frame 1 save-preset a.json\n"
            "frame 2 set sss.maps=8\n"
            "frame 3 set material=Ketchup\n"
            "frame 4 set material.eta=1.4\n"
            "frame 5 key ctrl+z\n"
            "frame 5 key ctrl+z\n"
            "frame 5 key ctrl+z\n"
            "frame 6 save-preset b.json\n"
            "frame 7 key ctrl+y\n"
            "frame 8 save-preset c.json\n");
  const auto r = test::runUnderXvfb(tallowLine({"view", "--preset", "blob", "--paused", "--fps", "30", "--frames", "9",
                                                "--script", "edits.txt", "--stats", "stats.json"}),
                                    dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const json stats = readJson(dir.path() / "stats.json");
  const json& frames = stats["frames"];
  const std::vector<json> states = parameterStates(stats);
  // The material edit kept the measured material's name, marked.
  EXPECT_EQ(frames[4]["changed"]["material"], "Ketchup (modified)");
  // Three undos: every value as the preset had it, and the saved preset the same file, byte for byte.
  EXPECT_EQ(states[5], states[0]);
  EXPECT_FALSE(frames[5]["view"]["can_undo"].get<bool>());
  EXPECT_TRUE(frames[5]["view"]["can_redo"].get<bool>());
  const auto slurp = [&](const char* name) { return readText(dir.path() / name); };
  ASSERT_FALSE(slurp("a.json").empty());
  EXPECT_EQ(slurp("b.json"), slurp("a.json"));
  // Redo: the first edit again, and only it.
  EXPECT_EQ(frames[7]["changed"], json({{"sss.maps", 8}}));
  EXPECT_EQ(json::parse(slurp("c.json"))["settings"]["sss.maps"], 8);
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
  test::expectOneErrorLine(r, expected);
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
  expectCleanFailure(runTallow({"view", "--size", "64x36", "--frames", "1", "--screenshot", p("a.png")}, noDisplay),
                     "no display: --screenshot needs the window", dir, inputs);
  // Issue 40: mistakes that would not end, or end silently.
  expectCleanFailure(runTallow({"view", "--screenshot", p("a.png")}, noDisplay),
                     "--screenshot: saved after the last frame, so it needs --frames N", dir, inputs);
  expectCleanFailure(runTallow({"view", "--save-preset", p("a.json")}, noDisplay),
                     "--save-preset: saved after the last frame, so it needs --frames N", dir, inputs);
  expectCleanFailure(runTallow({"view", "--debug-view", "difference"}, noDisplay),
                     "--debug-view difference: the difference view needs --reference REF.exr", dir, inputs);
  expectCleanFailure(runTallow({"view", "--max-step", "-1"}, noDisplay), "--max-step: must be in [0, 60] seconds", dir,
                     inputs);
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
  dir.write("diff.txt", "frame 2 debug difference\n");
  expectCleanFailure(runTallow({"view", "--script", p("diff.txt")}, noDisplay),
                     p("diff.txt") + ":1:9: debug: the difference view needs --reference", dir,
                     {"bad.txt", "diff.txt", "late.txt", "ref.exr", "shot.txt", "small.exr"});
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
  // Frame 1 keeps frame 0's history (sss.history: the blob moved for 0.1 s) and frame 2 shows the same
  // instant, but its change of K restarts the maps.
  EXPECT_EQ(frames[1]["sss"]["frames_accumulated"], 2);
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
