#pragma once
// An output folder (--out DIR of capture, bench, probe profile) has one owner at a time: the run
// holds an advisory lock (flock(2)) on DIR/.tallow.lock for its lifetime, whose text says who holds
// it, so that a second run into the same folder refuses at once with one line naming the holder,
// instead of interleaving its frames with the first. The kernel releases the lock of a process that
// dies, even by SIGKILL, so a stale lock file never blocks a later run. A rerun clears what an
// earlier run of the same command left (its frames, tables, pictures and stale temporaries) before
// it writes anything of its own, so the folder never mixes two runs (docs/commands.md).
#include <filesystem>
#include <string>
#include <vector>

namespace tallow::app {

/// The lock file's name in an output folder.
inline constexpr const char* kOutputLockName = ".tallow.lock";

class OutputFolder {
 public:
  /// Creates `dir` (and the folders above it that are missing) and takes its lock for `command`
  /// ("capture"). Throws InputError `OPTION: DIR is in use by another run (tallow capture, pid N,
  /// started …)` when another process holds it, or when the folder cannot be created.
  OutputFolder(const std::filesystem::path& dir, const std::string& command, const std::string& option = "--out");
  /// Releases the lock and removes the lock file; removes the folders it created when nothing was
  /// written into them.
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  const std::filesystem::path& path() const { return dir_; }

  /// Removes the entries of the folder whose names match one of `patterns` (fnmatch(3) globs, e.g.
  /// "frame_[0-9]*.png", "rows"; folders are removed with what they hold), and every temporary an
  /// earlier run of ours left behind (`.NAME.tmp-…` of those names, `.tallow-plot-…`). Returns how
  /// many entries went. Only the holder of the lock can be writing them, so none is in use.
  std::size_t clearEarlierRun(const std::vector<std::string>& patterns);

 private:
  std::filesystem::path dir_, lock_;
  std::vector<std::filesystem::path> created_;  ///< folders this run created, deepest first
  int fd_ = -1;
};

}  // namespace tallow::app
