#pragma once
// Progress of a long command (capture's frames, reference's passes, bench's reference and rows) on
// stderr: on a terminal a bar redrawn in place with the elapsed time and an estimate of the time
// left; otherwise (a log file, a pipe, CI) one line per step, at most one a second, so that quick
// runs stay silent and long ones leave a readable trail. TALLOW_PROGRESS=bar|lines|off overrides
// the choice (scripts that log a terminal session, tests).
#include <cstdio>
#include <functional>
#include <mutex>
#include <string>

namespace tallow::app {

enum class ProgressMode { Bar, Lines, Off };
/// $TALLOW_PROGRESS when set to bar, lines or off; else Bar when stderr is a terminal, Lines otherwise.
ProgressMode progressMode();

/// Where a task stands, for the formatters below.
struct ProgressState {
  std::string task;    ///< "capture", "reference", "bench"
  std::string unit;    ///< what a step is: "frame", "pass", "row"
  int done = 0;        ///< steps finished
  int total = 0;       ///< steps in all (an estimate where the task says so); 0: unknown
  double elapsedS = 0.0;
  std::string detail;  ///< e.g. "relative error 3.1% (target 2%)"
};

/// "12 s", "3 min 05 s", "2 h 04 min".
std::string formatDuration(double seconds);
/// Seconds left at the rate so far (elapsed / done per step); negative when unknown (nothing done,
/// or no total).
double secondsLeft(int done, int total, double elapsedS);
/// "capture: frame 12 of 40 (30%), 25 s, about 58 s left; detail" (without a total: "frame 12, 25 s").
std::string progressLine(const ProgressState& state);
/// One terminal line of at most `columns` - 1 characters:
/// "capture [########----------------]  12/40 frames  30%  25 s, 58 s left  detail".
std::string progressBar(const ProgressState& state, int columns);

class Progress {
 public:
  /// Seconds on a monotonic clock; injectable for tests.
  using Clock = std::function<double()>;

  Progress(std::string task, std::string unit, int total, ProgressMode mode = progressMode(), std::FILE* out = stderr,
           Clock clock = {});
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  /// Changes the number of steps (an estimate that improves as the task runs).
  void setTotal(int total) {
    const std::lock_guard lock(mutex_);
    total_ = total;
  }
  /// Reports `done` steps finished (never fewer than reported before: capture's render thread and
  /// its writer's thread both report, the writer a step behind; each call is safe from any thread): redraws the bar (at most 10 times a second, and at the last
  /// step), or prints a line when a second has passed since the last one (or since the start).
  void update(int done, const std::string& detail = "");
  /// Prints a line of the task's own (a finished row, a warning) without tearing the bar.
  void print(const std::string& line, std::FILE* stream);
  /// Clears the bar (the destructor does too); lines mode prints nothing more.
  void finish();

 private:
  ProgressState state(double now) const;
  void draw(double now);

  std::string task_, unit_;
  int total_ = 0, done_ = 0;
  std::string detail_;
  ProgressMode mode_;
  std::FILE* out_;
  Clock clock_;
  double start_ = 0.0, last_ = 0.0;
  bool barShown_ = false;
  std::mutex mutex_;  ///< update, print and finish from several threads
};

}  // namespace tallow::app
