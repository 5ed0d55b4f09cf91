// Long runs through the real executable: capture streams its frames (memory flat over many frames,
// stats.json rewritten after each), and SIGINT or SIGTERM in the middle of capture, reference and
// bench stops them with every file written whole, their metadata saying so, the exit status 130 or
// 143 and no temporary file left. Workloads are long enough that the signal always lands mid-run on
// a loaded 2-core machine, and are cut short by it, so each test takes seconds.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <string>

#include "gpu/image_io.h"
#include "support/run_tallow.h"
#include "support/temp_dir.h"

namespace tallow {
namespace {

using json = nlohmann::json;
using test::runTallow;
using test::TallowProcess;
namespace fs = std::filesystem;

/// Long enough to wait for the process to be under way on a slow machine.
constexpr std::chrono::seconds kStartTimeout{240};

json readJson(const fs::path& file) {
  std::ifstream in(file);
  return json::parse(in);
}

/// Files anywhere under `dir` whose name starts with '.': the atomic writers' temporaries
/// (`.NAME.tmp-…`), gnuplot's scripts and data, ffmpeg's log.
std::vector<std::string> hiddenFiles(const fs::path& dir) {
  std::vector<std::string> found;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.path().filename().string().front() == '.') found.push_back(e.path().string());
  return found;
}

int countLines(const fs::path& file) {
  std::ifstream in(file);
  return static_cast<int>(std::count(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>(), '\n'));
}

// A blob sequence at a small size: a fraction of a second per frame on llvmpipe, 400 frames.
std::vector<std::string> longCapture(const fs::path& out) {
  return {"capture", "--preset", "blob", "--size", "96x64", "--set", "sss.map_size=32", "--set", "sss.maps=4",
          "--set", "field.res=24", "--frames", "400", "--fps", "30", "--out", out.string()};
}

/// The capture's frames are whole and stats.json lists exactly them; returns how many.
int checkCaptureStoppedCleanly(const fs::path& out, const std::string& signal) {
  const json stats = readJson(out / "stats.json");
  EXPECT_EQ(stats["run"]["state"], "interrupted");
  EXPECT_EQ(stats["run"]["stop_reason"], signal);
  EXPECT_EQ(stats["run"]["frames_requested"], 400);
  const int n = stats["run"]["frames_written"].get<int>();
  EXPECT_EQ(static_cast<int>(stats["frames"].size()), n);
  EXPECT_GE(n, 3);
  EXPECT_LT(n, 400);
  for (int i = 0; i < n; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%04d", i);
    const gpu::Image png = gpu::readPng(out / (std::string(name) + ".png"));  // throws if cut short
    const gpu::Image exr = gpu::readExr(out / (std::string(name) + ".exr"));
    EXPECT_EQ(png.width, 96);
    EXPECT_EQ(exr.height, 64);
  }
  char next[32];
  std::snprintf(next, sizeof next, "frame_%04d.png", n);
  EXPECT_FALSE(fs::exists(out / next)) << "a frame beyond those stats.json lists";
  EXPECT_TRUE(stats["summary"].is_object());
  EXPECT_TRUE(stats["provenance"]["command_line"].get<std::string>().find("capture") != std::string::npos);
  return n;
}

/// A capture with --video (when ffmpeg is there) stopped by `signal`: every frame whole, the exit
/// status 128 + signal, no temporary left, the video closed with the frames written.
void checkCaptureWithVideoStops(int signal, const std::string& name) {
  test::TempDir dir;
  const fs::path out = dir.path() / "o", video = dir.path() / "v.mp4";
  const bool ffmpeg = std::system("command -v ffmpeg >/dev/null 2>&1 && command -v ffprobe >/dev/null 2>&1") == 0;
  std::vector<std::string> args = longCapture(out);
  if (ffmpeg) args.insert(args.end(), {"--video", video.string()});
  TallowProcess p(args);
  ASSERT_TRUE(p.waitUntil([&] { return fs::exists(out / "frame_0002.png"); }, kStartTimeout)) << p.err();
  p.signal(signal);
  EXPECT_EQ(p.wait(), 128 + signal) << p.err();
  const int n = checkCaptureStoppedCleanly(out, name);
  EXPECT_NE(p.err().find("capture stopped by " + name + " after " + std::to_string(n) + " of 400 frame(s)"),
            std::string::npos)
      << p.err();
  EXPECT_EQ(hiddenFiles(dir.path()), std::vector<std::string>{});
  if (ffmpeg) {
    // The video holds the frames written, closed properly (ffprobe, not our code, reads it).
    const std::string probe = "ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames "
                              "-of json '" + video.string() + "' > '" + (dir.path() / "probe.json").string() + "'";
    ASSERT_EQ(std::system(probe.c_str()), 0);
    EXPECT_EQ(readJson(dir.path() / "probe.json")["streams"][0]["nb_read_frames"], std::to_string(n));
  }
}

TEST(LongRuns, CaptureStopsAfterTheFrameInHandOnSigint) { checkCaptureWithVideoStops(SIGINT, "SIGINT"); }

TEST(LongRuns, CaptureStopsOnSigtermWith143) {
  test::TempDir dir;
  const fs::path out = dir.path() / "o";
  TallowProcess p(longCapture(out));
  ASSERT_TRUE(p.waitUntil([&] { return fs::exists(out / "frame_0002.png"); }, kStartTimeout)) << p.err();
  p.signal(SIGTERM);
  EXPECT_EQ(p.wait(), 143) << p.err();
  checkCaptureStoppedCleanly(out, "SIGTERM");
  EXPECT_EQ(hiddenFiles(dir.path()), std::vector<std::string>{});
}

// Issue 37, point 5: a dropped ssh session sends SIGHUP, which ended capture with stats.json saying
// "running" forever, reference with nothing written and --video with its temporaries left.
TEST(LongRuns, CaptureStopsOnSighupWith129AndNoTemporaries) { checkCaptureWithVideoStops(SIGHUP, "SIGHUP"); }

TEST(LongRuns, ACaptureKilledOutrightLeavesARecordOfEveryFrameItFinished) {
  // SIGKILL cannot be handled: stats.json says "running" and names the JSON Lines file, whose lines
  // are the frames written (docs/commands.md).
  test::TempDir dir;
  const fs::path out = dir.path() / "o";
  TallowProcess p(longCapture(out));
  ASSERT_TRUE(p.waitUntil([&] { return fs::exists(out / "frame_0003.png"); }, kStartTimeout)) << p.err();
  p.signal(SIGKILL);
  EXPECT_EQ(p.wait(), 128 + SIGKILL);
  const json stats = readJson(out / "stats.json");
  EXPECT_EQ(stats["run"]["state"], "running");
  ASSERT_EQ(stats["run"]["frames_file"], "stats.frames.jsonl");
  std::ifstream lines(out / "stats.frames.jsonl");
  int n = 0;
  for (std::string line; std::getline(lines, line); ++n) EXPECT_EQ(json::parse(line)["index"], n);
  EXPECT_GE(n, 3);
  for (int i = 0; i < n; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%04d.exr", i);
    EXPECT_EQ(gpu::readExr(out / name).width, 96) << name;
  }
}

TEST(LongRuns, ReferenceWritesThePassesDoneOnSighup) {
  test::TempDir dir;
  const fs::path ref = dir.path() / "ref.exr";
  TallowProcess p({"reference", "--preset", "slab", "--size", "32x24", "--spp", "100000", "--points", "20000", "--out",
                   ref.string()},
                  {"TALLOW_PROGRESS=lines"});
  ASSERT_TRUE(p.waitUntil([&] { return p.err().find("reference: pass ") != std::string::npos; }, kStartTimeout))
      << p.err();
  p.signal(SIGHUP);
  EXPECT_EQ(p.wait(), 129) << p.err();
  EXPECT_EQ(gpu::readExr(ref).width, 32);
  EXPECT_EQ(gpu::readExr(dir.path() / "ref_stderr.exr").height, 24);
  EXPECT_EQ(gpu::readExrStringAttributes(ref).at("tallow.stopped_by"), "SIGHUP");
  EXPECT_EQ(hiddenFiles(dir.path()), std::vector<std::string>{});
}

TEST(LongRuns, CaptureMemoryStaysFlatOverManyFrames) {
  // 160x120 frames are 300 KB each as float RGBA: a capture that kept them would grow by 12 MB over
  // the 40 frames after the tenth. The process's resident memory after each frame is in stats.json.
  test::TempDir dir;
  const fs::path out = dir.path() / "o";
  const auto start = std::chrono::steady_clock::now();
  const auto r = runTallow({"capture", "--preset", "slab", "--size", "160x120", "--set", "method=albedo", "--set",
                            "render.shadows=false", "--frames", "50", "--out", out.string()},
                           {"TALLOW_PROGRESS=lines"});
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const json stats = readJson(out / "stats.json");
  EXPECT_EQ(stats["run"]["state"], "complete");
  const json& frames = stats["frames"];
  ASSERT_EQ(frames.size(), 50u);
  // After ten frames allocations have settled (buffers, PNG and EXR writers); from there on, at most
  // the size of eight frames more, where keeping the frames would add forty. Since issue 39 a frame
  // is written on the writer's thread while the next is fetched: up to three frames' two images
  // (written, queued, fetched) live at once beside the frame before, and the resident size is read
  // while they come and go (measured: 4.6 frames' worth once under load; a tenth of a frame before).
  constexpr double kFrameBytes = 160.0 * 120.0 * 16.0;
  const double settled = frames[10]["rss_bytes"].get<double>();
  double largest = 0.0;
  for (std::size_t i = 10; i < frames.size(); ++i) largest = std::max(largest, frames[i]["rss_bytes"].get<double>());
  std::printf("[ memory  ] resident after frame 10: %.1f MiB, largest after: %.1f MiB (+%.2f frames' worth)\n",
              settled / 1048576.0, largest / 1048576.0, (largest - settled) / kFrameBytes);
  EXPECT_GT(settled, 0.0);
  EXPECT_LT(largest - settled, 8.0 * kFrameBytes);
  // Progress in a log: one line a second at most (and a final summary on stdout).
  const int progressLines = static_cast<int>(std::count(r.err.begin(), r.err.end(), '\n'));
  EXPECT_LE(progressLines, static_cast<int>(seconds) + 1) << r.err;
  if (seconds > 2.5) {
    EXPECT_GE(progressLines, 1) << "a run of " << seconds << " s said nothing";
  }
}

TEST(LongRuns, ReferenceWritesThePassesDoneOnSigint) {
  test::TempDir dir;
  const fs::path ref = dir.path() / "ref.exr";
  // 20000 points a pass: passes of a fraction of a second (the automatic count takes seconds).
  TallowProcess p({"reference", "--preset", "slab", "--size", "32x24", "--spp", "100000", "--points", "20000", "--out",
                   ref.string()},
                  {"TALLOW_PROGRESS=lines"});
  // The progress line shows that passes are done (the first comes after a second).
  ASSERT_TRUE(p.waitUntil([&] { return p.err().find("reference: pass ") != std::string::npos; }, kStartTimeout))
      << p.err();
  p.signal(SIGINT);
  EXPECT_EQ(p.wait(), 130) << p.err();
  const gpu::Image image = gpu::readExr(ref);
  const gpu::Image standardError = gpu::readExr(dir.path() / "ref_stderr.exr");
  EXPECT_EQ(image.width, 32);
  EXPECT_EQ(standardError.height, 24);
  const auto attributes = gpu::readExrStringAttributes(ref);
  EXPECT_EQ(attributes.at("tallow.complete"), "no");
  EXPECT_EQ(attributes.at("tallow.stopped_by"), "SIGINT");
  const int passes = std::stoi(attributes.at("tallow.passes"));
  EXPECT_GE(passes, 1);
  EXPECT_LT(passes, 100000);
  EXPECT_EQ(attributes.at("tallow.spp"), attributes.at("tallow.passes"));
  if (passes >= 2) {
    EXPECT_GT(std::stod(attributes.at("tallow.rel_error")), 0.0);
  }
  EXPECT_NE(attributes.at("tallow.command_line").find("reference"), std::string::npos);
  EXPECT_EQ(gpu::readExrStringAttributes(dir.path() / "ref_stderr.exr").at("tallow.passes"), attributes.at("tallow.passes"));
  // The progress said how far it was and the estimated time left.
  EXPECT_TRUE(std::regex_search(p.err(), std::regex("reference: pass [0-9]+ of 100000 \\([0-9]+%\\), .*left")))
      << p.err();
  EXPECT_EQ(hiddenFiles(dir.path()), std::vector<std::string>{});
}

/// The slab at 8x6 against a 4-pass reference: rows of a few tiny frames each.
class LongBench : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new test::TempDir();
    const auto r = runTallow({"reference", "--preset", "slab", "--size", "8x6", "--spp", "4", "--out",
                              (dir_->path() / "ref.exr").string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  static test::TempDir* dir_;
};
test::TempDir* LongBench::dir_ = nullptr;

TEST_F(LongBench, SigintKeepsTheRowsFinished) {
  test::TempDir dir;
  const fs::path out = dir.path() / "bench";
  TallowProcess p({"bench", "--preset", "slab", "--size", "8x6", "--set", "sss.map_size=64", "--set",
                   "sss.light_map_size=64", "--set", "sss.frames=3", "--reference", (dir_->path() / "ref.exr").string(),
                   "--methods", "radiosity-maps,no-cache,albedo", "--sweep", "sss.samples=1,2,3,4,5,6,7,8", "--out",
                   out.string()});
  ASSERT_TRUE(p.waitUntil([&] { return fs::exists(out / "bench.csv") && countLines(out / "bench.csv") >= 2; },
                          kStartTimeout))
      << p.err();
  p.signal(SIGINT);
  EXPECT_EQ(p.wait(), 130) << p.err();
  const json bench = readJson(out / "bench.json");
  EXPECT_EQ(bench["run"]["state"], "interrupted");
  const int rows = bench["run"]["rows_written"].get<int>();
  EXPECT_GE(rows, 1);
  // 8 rows each for the maps and no-cache, which read sss.samples; albedo does not: one row (17).
  EXPECT_LT(rows, 17);
  EXPECT_EQ(static_cast<int>(bench["rows"].size()), rows);
  EXPECT_EQ(countLines(out / "bench.csv"), rows + 1);
  for (const json& row : bench["rows"]) {
    const fs::path folder = out / row["folder"].get<std::string>();
    EXPECT_EQ(gpu::readExr(folder / "last.exr").width, 8) << folder;
    EXPECT_TRUE(fs::is_regular_file(folder / "last.png")) << folder;
    // The console line of each row carries the reference's ε beside the row's error.
    EXPECT_NE(p.out().find(row["row"].get<std::string>()), std::string::npos);
  }
  EXPECT_NE(p.out().find("(reference ε "), std::string::npos) << p.out();
  EXPECT_NE(p.err().find("bench stopped by SIGINT after " + std::to_string(rows) + " of 17 row(s)"), std::string::npos)
      << p.err();
  EXPECT_EQ(hiddenFiles(dir.path()), std::vector<std::string>{});
}

TEST_F(LongBench, SigintDuringItsReferenceWritesThePassesDone) {
  test::TempDir dir;
  const fs::path out = dir.path() / "bench";
  TallowProcess p({"bench", "--preset", "slab", "--size", "32x24", "--methods", "albedo", "--ref-spp", "100000",
                   "--ref-points", "20000", "--out", out.string()},
                  {"TALLOW_PROGRESS=lines"});
  // Not silent while it builds its reference: the progress shows its passes.
  ASSERT_TRUE(p.waitUntil([&] { return p.err().find("reference: pass ") != std::string::npos; }, kStartTimeout))
      << p.err();
  p.signal(SIGINT);
  EXPECT_EQ(p.wait(), 130) << p.err();
  const auto attributes = gpu::readExrStringAttributes(out / "reference.exr");
  EXPECT_EQ(attributes.at("tallow.complete"), "no");
  EXPECT_GE(std::stoi(attributes.at("tallow.passes")), 1);
  EXPECT_EQ(gpu::readExr(out / "reference_stderr.exr").width, 32);
  const json bench = readJson(out / "bench.json");
  EXPECT_EQ(bench["run"]["state"], "interrupted");
  EXPECT_EQ(bench["run"]["rows_written"], 0);
  EXPECT_EQ(bench["references"][0]["complete"], false);
  EXPECT_EQ(hiddenFiles(dir.path()), std::vector<std::string>{});
}

// capture --reference (issue 17, point 3): every frame's error against one reference in stats.json,
// checked here against references whose answer is known: the capture's own frame (error 0 up to the
// EXR's half floats) and that frame doubled (mean ratio 1/2, relative RMSE 1/2); plus the
// translucent pixels' frame-to-frame change, and one line for a reference of another size.
TEST(CaptureReference, EachFrameIsComparedWithTheReferenceAndTheTranslucentChangeIsRecorded) {
  test::TempDir dir;
  const std::vector<std::string> scene = {"capture", "--preset", "slab", "--size", "64x48", "--set", "sss.maps=4",
                                          "--set", "sss.map_size=64", "--set", "sss.light_map_size=64", "--frames", "2"};
  const auto withOut = [&](const fs::path& out, std::vector<std::string> extra) {
    std::vector<std::string> args = scene;
    args.insert(args.end(), {"--out", out.string()});
    args.insert(args.end(), extra.begin(), extra.end());
    return runTallow(args);
  };
  const fs::path first = dir.path() / "first";
  auto r = withOut(first, {"--exr-float"});  // the reference below is this frame, bit for bit
  ASSERT_EQ(r.exitCode, 0) << r.err;
  json stats = readJson(first / "stats.json");
  EXPECT_TRUE(stats["frames"][0]["translucent_change"].is_null()) << "no frame before the first";
  ASSERT_TRUE(stats["frames"][1]["translucent_change"].is_number());
  // The slab is still: the second frame accumulates the maps further, a small change, not none.
  EXPECT_GT(stats["frames"][1]["translucent_change"].get<double>(), 0.0);
  EXPECT_LT(stats["frames"][1]["translucent_change"].get<double>(), 0.5);
  EXPECT_TRUE(stats["frames"][1]["reference_error"].is_null()) << "no --reference";

  // The first run's second frame as the reference, every pixel marked as the object's.
  const gpu::Image frame = gpu::readExr(first / "frame_0001.exr");
  gpu::Image mask(frame.width, frame.height);
  for (auto& p : mask.pixels) p = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
  gpu::Image doubled = frame;
  for (auto& p : doubled.pixels) p = glm::vec4(2.0f * glm::vec3(p), p.a);
  gpu::writeExr(dir.path() / "same.exr", frame, gpu::ExrPixelType::Float, {});
  gpu::writeExr(dir.path() / "same_stderr.exr", mask, gpu::ExrPixelType::Float, {});
  gpu::writeExr(dir.path() / "doubled.exr", doubled, gpu::ExrPixelType::Float, {});
  gpu::writeExr(dir.path() / "doubled_stderr.exr", mask, gpu::ExrPixelType::Float, {});

  // Float EXRs here too: a frame is compared as its EXR stores it (half floats by default).
  r = withOut(dir.path() / "same", {"--exr-float", "--reference", (dir.path() / "same.exr").string()});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  stats = readJson(dir.path() / "same" / "stats.json");
  const json& same = stats["frames"][1]["reference_error"];
  ASSERT_TRUE(same.is_object()) << stats["frames"][1].dump();
  EXPECT_EQ(same["pixels"], 64 * 48);
  EXPECT_LT(same["rel_rmse"].get<double>(), 1e-6) << "the same render (llvmpipe is deterministic)";
  EXPECT_NEAR(same["mean_ratio"].get<double>(), 1.0, 1e-6);
  EXPECT_GT(stats["frames"][0]["reference_error"]["rel_rmse"].get<double>(), 0.0) << "frame 1 has fewer frames";

  r = withOut(dir.path() / "doubled", {"--exr-float", "--reference", (dir.path() / "doubled.exr").string()});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const json doubledError = readJson(dir.path() / "doubled" / "stats.json")["frames"][1]["reference_error"];
  EXPECT_NEAR(doubledError["mean_ratio"].get<double>(), 0.5, 1e-6);
  EXPECT_NEAR(doubledError["upper_mean_ratio"].get<double>(), 0.5, 1e-6);
  EXPECT_NEAR(doubledError["lower_mean_ratio"].get<double>(), 0.5, 1e-6);
  EXPECT_NEAR(doubledError["rel_rmse"].get<double>(), 0.5, 1e-6) << "|x − 2x| / RMS(2x)";

  // Another size: one line, nothing rendered.
  const fs::path wrong = dir.path() / "wrong";
  r = runTallow({"capture", "--preset", "slab", "--size", "32x24", "--out", wrong.string(), "--reference",
                 (dir.path() / "same.exr").string()});
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_EQ(test::lineCount(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("is 64x48 but the capture renders 32x24"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(wrong / "stats.json"));
}

}  // namespace
}  // namespace tallow
