#pragma once
// Runs the `tallow` executable as a user would, capturing exit status and output.
#include <sys/types.h>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "support/temp_dir.h"

namespace tallow::test {

struct CommandResult {
  int exitCode = -1;
  std::string out;  ///< stdout
  std::string err;  ///< stderr
};

/// Runs TALLOW_TEST_BINARY (or $TALLOW_TEST_TALLOW when set) with `args` (each shell-quoted),
/// with `env` ("NAME=value") prepended.
CommandResult runTallow(const std::vector<std::string>& args, const std::vector<std::string>& env = {});

/// Number of lines in `text` that are not empty.
int lineCount(const std::string& text);

/// TALLOW_TEST_BINARY running in the background (stdout and stderr to files), for tests that act
/// while it runs: signal it once its output shows it is under way. Killed if still running at the end.
class TallowProcess {
 public:
  TallowProcess(const std::vector<std::string>& args, const std::vector<std::string>& env = {});
  ~TallowProcess();
  TallowProcess(const TallowProcess&) = delete;
  TallowProcess& operator=(const TallowProcess&) = delete;

  /// Polls `ready` every 20 ms until it holds (true), the process ends or `timeout` passes (false).
  bool waitUntil(const std::function<bool()>& ready, std::chrono::seconds timeout);
  bool running();
  void signal(int sig);
  /// Waits for the end; the exit status as a shell reports it (128 + the signal when one ended it).
  int wait();
  /// wait(), reading first how many bytes the process passed to write(2) and its kin, all threads,
  /// as the kernel counts them (wchar of /proc/PID/io, kept until the process is reaped): files,
  /// pipes and terminals alike, so an upper bound of what it wrote to disk.
  int wait(std::uint64_t& bytesWritten);
  std::string out() const;
  std::string err() const;

 private:
  TempDir io_;
  pid_t pid_ = -1;
  int status_ = -1;
};

}  // namespace tallow::test
