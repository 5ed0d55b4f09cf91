#pragma once
// Running another program (gnuplot, ffmpeg) without a shell: posix_spawn with an argument vector,
// so that nothing in a file name or a caption is ever parsed as a command. The child gets a process
// group of its own (the terminal's Ctrl-C reaches Tallow only, which finishes the step in hand and
// stops the child itself), /dev/null or a pipe as stdin, and its stderr in a file of the caller's.
#include <sys/types.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace tallow::app {

/// The program `name` on PATH, or the executable `$environmentVariable` names when that is set and
/// not empty (TALLOW_FFMPEG); empty when there is none.
std::filesystem::path findExecutable(const std::string& name, const char* environmentVariable = nullptr);

struct SpawnOptions {
  std::filesystem::path workingFolder;  ///< empty: ours
  int stdinFd = -1;                     ///< a descriptor to read from (a pipe's end); -1: /dev/null
  /// Created for the child's stderr with O_EXCL (it must not exist); empty: /dev/null.
  std::filesystem::path stderrFile;
};

/// Starts `program` with `arguments` (argv[1]…; argv[0] is the program's path). Throws
/// std::runtime_error `cannot run PROGRAM: REASON` when it cannot be started.
pid_t spawnProgram(const std::filesystem::path& program, const std::vector<std::string>& arguments,
                   const SpawnOptions& options = {});

/// Waits for the child (retrying on EINTR) and returns its wait status (WIFEXITED…).
int waitProgram(pid_t pid);

/// spawnProgram then waitProgram: true when the program exited with status 0.
bool runProgram(const std::filesystem::path& program, const std::vector<std::string>& arguments,
                const SpawnOptions& options = {});

/// The last line of a text file with something besides blanks and gnuplot's `^` marker in it (a
/// program's error), or "" when there is none or the file cannot be read.
std::string lastMessageLine(const std::filesystem::path& file);

}  // namespace tallow::app
