// Issue 37 without GL: the pieces that keep outputs safe — gnuplot literals that expand nothing,
// temporaries no one can predict or hijack, one owner per output folder, stats written in bytes
// proportional to the frames, names checked for UTF-8. Through the executable: output_safety_gltest.cpp.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "app/commands/frame_stats.h"
#include "app/commands/gnuplot.h"
#include "app/commands/output_folder.h"
#include "app/commands/stats_writer.h"
#include "app/config/input_error.h"
#include "gpu/atomic_file.h"
#include "gpu/utf8.h"
#include "support/temp_dir.h"

namespace tallow {
namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(GnuplotString, IsASingleQuotedLiteralThatExpandsNothing) {
  // gnuplot's manual: no backquote command, no @macro and no backslash escape inside single quotes;
  // a single quote is written twice.
  EXPECT_EQ(app::gnuplotString("a`touch x`b"), "'a`touch x`b'");
  EXPECT_EQ(app::gnuplotString("o';touch y;'"), "'o'';touch y;'''");
  EXPECT_EQ(app::gnuplotString("@macro \\n $(x)"), "'@macro \\n $(x)'");
  // A newline would end the command and start another: every control character becomes a space.
  EXPECT_EQ(app::gnuplotString("x\nsystem('touch z')\r\t\x7f"), "'x system(''touch z'')   '");
  EXPECT_EQ(app::gnuplotString(""), "''");
  EXPECT_EQ(app::gnuplotString("≥ 5%"), "'≥ 5%'");
}

TEST(Temporaries, NamesAreRandomAndPrivateFoldersOurs) {
  std::set<std::string> tokens;
  for (int i = 0; i < 200; ++i) {
    const std::string t = gpu::randomToken();
    EXPECT_EQ(t.size(), 12u);
    EXPECT_EQ(t.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789"), std::string::npos) << t;
    tokens.insert(t);
  }
  EXPECT_EQ(tokens.size(), 200u) << "a repeated token among 200 of 62 bits";

  test::TempDir dir;
  fs::path kept;
  {
    const gpu::PrivateFolder folder(dir.path(), "tallow-plot");
    kept = folder.path();
    struct stat st {};
    ASSERT_EQ(::lstat(folder.path().c_str(), &st), 0);
    EXPECT_TRUE(S_ISDIR(st.st_mode));
    EXPECT_EQ(st.st_mode & 0777, 0700u) << "only its owner may create or replace files in it";
    EXPECT_EQ(folder.name().rfind(".tallow-plot-", 0), 0u) << folder.name();
    dir.write(folder.name() + "/inside/data.bin", "x");
  }
  EXPECT_FALSE(fs::exists(kept)) << "removed with what it held";

  // A temporary of a writer is created afresh with O_EXCL under a name no one could plant a link at.
  gpu::PendingFile a(dir.path() / "f.png"), b(dir.path() / "f.png");
  EXPECT_NE(a.temporary(), b.temporary());
  EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(a.temporary())));
}

TEST(OutputFolder, ASecondOwnerIsRefusedWithTheHoldersName) {
  test::TempDir dir;
  const fs::path out = dir.path() / "deep" / "out";
  {
    const app::OutputFolder first(out, "capture");
    EXPECT_TRUE(fs::is_directory(out));
    EXPECT_NE(slurp(out / app::kOutputLockName).find("tallow capture, pid " + std::to_string(::getpid())),
              std::string::npos);
    // flock(2) locks an open file description: a second open in this very process conflicts too.
    try {
      const app::OutputFolder second(out, "bench");
      FAIL() << "a second owner was let in";
    } catch (const app::InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("--out: "), std::string::npos) << what;
      EXPECT_NE(what.find("is in use by another run (tallow capture, pid " + std::to_string(::getpid())),
                std::string::npos)
          << what;
    }
  }
  // Released: the lock file goes, and so do the folders it created, when nothing was written.
  EXPECT_FALSE(fs::exists(dir.path() / "deep"));
  {
    const app::OutputFolder again(out, "capture");
    dir.write("deep/out/frame_0000.png", "p");
  }
  EXPECT_TRUE(fs::exists(out / "frame_0000.png"));
  EXPECT_FALSE(fs::exists(out / app::kOutputLockName));
}

TEST(OutputFolder, ClearingTakesTheEarlierRunsOutputsAndTemporariesOnly) {
  test::TempDir dir;
  for (const char* name : {"frame_0000.png", "frame_0012.exr", "stats.json", ".frame_0003.png.tmp-99-abc",
                           ".stats.json.tmp-1-x", "notes.txt", "frame_final.png", "rows/a/first.png"})
    dir.write(name, "x");
  fs::create_directory(dir.path() / ".tallow-plot-old");
  fs::create_symlink(dir.path() / "notes.txt", dir.path() / "frame_0001.png");
  app::OutputFolder folder(dir.path(), "capture");
  EXPECT_EQ(folder.clearEarlierRun({"frame_[0-9]*.png", "frame_[0-9]*.exr", "stats.json", "rows"}), 8u);
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{app::kOutputLockName, "frame_final.png", "notes.txt"}));
  EXPECT_EQ(slurp(dir.path() / "notes.txt"), "x") << "a link is removed, never followed";
}

app::FrameRecord frame(int index, double wallMs, double gpuMs) {
  app::FrameRecord f;
  f.index = index;
  f.timeS = index / 30.0;
  f.wallMs = wallMs;
  f.gpu.passes.push_back({"sss.maps", gpuMs, 2.0 * gpuMs, 3.0 * gpuMs, std::nullopt});
  f.gpu.gpuTotalMs = gpuMs;
  f.gpu.cpuTotalMs = 2.0 * gpuMs;
  f.gpu.threadCpuTotalMs = 3.0 * gpuMs;
  return f;
}

TEST(StatsWriter, FramesAreAppendedAndStatsJsonIsWholeAtTheEnd) {
  test::TempDir dir;
  const fs::path stats = dir.path() / "stats.json";
  app::RunRecord run;
  run.command = "capture";
  run.framesRequested = 5;
  run.state = "running";
  {
    app::StatsWriter writer(stats);
    EXPECT_EQ(writer.framesFile(), dir.path() / "stats.frames.jsonl");
    const double wall[] = {5.0, 1.0, 4.0, 2.0, 3.0};
    for (int i = 0; i < 5; ++i) {
      writer.append(run, frame(i, wall[i], 10.0 * (i + 1)));
      // While it runs: one line a frame, and a stats.json that lists none of them.
      std::ifstream in(writer.framesFile());
      int lines = 0;
      for (std::string line; std::getline(in, line);) {
        EXPECT_EQ(nlohmann::json::parse(line)["index"], lines);
        ++lines;
      }
      EXPECT_EQ(lines, i + 1);
      const nlohmann::json running = nlohmann::json::parse(slurp(stats));
      EXPECT_EQ(running["run"]["state"], "running");
      EXPECT_EQ(running["run"]["frames_file"], "stats.frames.jsonl");
      EXPECT_FALSE(running.contains("frames"));
    }
    EXPECT_EQ(run.framesWritten, 5);
    run.state = "complete";
    writer.finish(run);
  }
  EXPECT_FALSE(fs::exists(dir.path() / "stats.frames.jsonl"));
  const nlohmann::json done = nlohmann::json::parse(slurp(stats));
  EXPECT_EQ(done["run"]["state"], "complete");
  EXPECT_EQ(done["run"]["frames_written"], 5);
  ASSERT_EQ(done["frames"].size(), 5u);
  for (int i = 0; i < 5; ++i) EXPECT_EQ(done["frames"][i]["index"], i);
  // Medians by hand: wall {1,2,3,4,5} → 3; GPU {10..50} → 30; the pass's CPU and thread times 60, 90.
  EXPECT_DOUBLE_EQ(done["summary"]["wall_ms_median"].get<double>(), 3.0);
  EXPECT_DOUBLE_EQ(done["summary"]["gpu_total_ms_median"].get<double>(), 30.0);
  EXPECT_DOUBLE_EQ(done["summary"]["gpu_ms_median"]["sss.maps"].get<double>(), 30.0);
  EXPECT_DOUBLE_EQ(done["summary"]["cpu_ms_median"]["sss.maps"].get<double>(), 60.0);
  EXPECT_DOUBLE_EQ(done["summary"]["thread_cpu_ms_median"]["sss.maps"].get<double>(), 90.0);
  EXPECT_EQ(done["summary"]["frames"], 5);
}

TEST(StatsWriter, NamesThatAreNotUtf8DoNotStopTheJson) {
  // Names are checked where they come in (checkOutputName, the preset and material readers); this
  // is the backstop: the run's record is written, with U+FFFD for the bad byte.
  test::TempDir dir;
  app::RunRecord run;
  run.presetName = "bad\xff name";
  app::StatsWriter writer(dir.path() / "stats.json");
  writer.finish(run);
  const nlohmann::json done = nlohmann::json::parse(slurp(dir.path() / "stats.json"));
  EXPECT_EQ(done["preset"]["name"], "bad\xEF\xBF\xBD name");
  EXPECT_EQ(done["frames"].size(), 0u);
}

TEST(Utf8, WellFormedSequencesOnly) {
  EXPECT_TRUE(gpu::validUtf8("plain ascii"));
  EXPECT_TRUE(gpu::validUtf8("σ_s mm⁻¹ → 𝄞"));
  EXPECT_EQ(gpu::firstInvalidUtf8("ab\xff"), 2u);
  EXPECT_EQ(gpu::firstInvalidUtf8("\xC0\xAF"), 0u) << "overlong '/'";
  EXPECT_EQ(gpu::firstInvalidUtf8("x\xED\xA0\x80"), 1u) << "a surrogate";
  EXPECT_EQ(gpu::firstInvalidUtf8("\xF4\x90\x80\x80"), 0u) << "above U+10FFFF";
  EXPECT_EQ(gpu::firstInvalidUtf8("ok\xE2\x82"), 2u) << "cut short";
  EXPECT_TRUE(gpu::validUtf8("\xF4\x8F\xBF\xBF")) << "U+10FFFF itself";
}

TEST(ReferenceErrorRecord, NonFinitePixelsAreCountedAndTheErrorIsNull) {
  gpu::Image image(4, 3), reference(4, 3), mask(4, 3);
  for (auto& p : image.pixels) p = glm::vec4(0.5f, 0.5f, 0.5f, 1.0f);
  for (auto& p : reference.pixels) p = glm::vec4(0.5f, 0.5f, 0.5f, 1.0f);
  for (auto& p : mask.pixels) p = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
  image.at(1, 1).r = std::nanf("");
  image.at(2, 1).g = -INFINITY;
  const nlohmann::json r = app::referenceErrorRecord(image, reference, mask);
  EXPECT_TRUE(r["rel_rmse"].is_null()) << r.dump();
  EXPECT_EQ(r["non_finite"]["image"], 2);
  EXPECT_EQ(r["non_finite"]["reference"], 0);
  gpu::ImageErrorOptions leaveOut;
  leaveOut.skipNonFinite = true;
  const nlohmann::json s = app::referenceErrorRecord(image, reference, mask, leaveOut);
  EXPECT_DOUBLE_EQ(s["rel_rmse"].get<double>(), 0.0);
  EXPECT_EQ(s["non_finite"]["left_out"], 2);
  EXPECT_EQ(s["pixels"], 10);
}

}  // namespace
}  // namespace tallow
