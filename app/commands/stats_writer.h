#pragma once
// stats.json written as a run goes, in bytes and memory that do not grow with the frames written so
// far: each frame's record is appended as one line to STEM.frames.jsonl beside it (JSON Lines), and
// stats.json, the run without its frames (state "running", frames_written, "frames_file"), is
// rewritten at most once a second. finish() writes stats.json whole, as it always was — the run,
// "frames" (one frame a line, read back from the JSON Lines file) and "summary" (their medians) —
// and removes the JSON Lines file. A run killed with SIGKILL leaves stats.json saying "running"
// beside a JSON Lines file with every frame finished. docs/commands.md.
#include <nlohmann/json.hpp>

#include <chrono>
#include <filesystem>
#include <string>

#include "app/commands/frame_stats.h"

namespace tallow::app {

/// "stats.frames.jsonl" for "stats.json": the JSON Lines file of a stats file.
std::filesystem::path framesFileOf(const std::filesystem::path& stats);

/// nlohmann::json::dump that never throws on text that is not UTF-8 (invalid bytes become U+FFFD):
/// every file name of a run goes into its JSON.
std::string dumpJson(const nlohmann::json& value, int indent = -1);

class StatsWriter {
 public:
  /// Nothing is written until the first frame or update().
  explicit StatsWriter(std::filesystem::path stats);
  /// Closes the JSON Lines file; without finish() it stays, the record of the frames.
  ~StatsWriter();
  StatsWriter(const StatsWriter&) = delete;
  StatsWriter& operator=(const StatsWriter&) = delete;

  /// Appends the frame's line (opening the file on the first frame) and counts it in run.framesWritten;
  /// then update(run).
  void append(RunRecord& run, const FrameRecord& frame);
  /// Rewrites stats.json (the run, no frames) when a second has passed since it last was, or `now`.
  void update(const RunRecord& run, bool now = false);
  /// stats.json whole: the run, its frames and their summary; then the JSON Lines file is removed.
  void finish(const RunRecord& run);

  const std::filesystem::path& statsFile() const { return stats_; }
  const std::filesystem::path& framesFile() const { return frames_; }

 private:
  std::filesystem::path stats_, frames_;
  int fd_ = -1;
  std::chrono::steady_clock::time_point lastUpdate_{};
  bool updated_ = false;
};

}  // namespace tallow::app
