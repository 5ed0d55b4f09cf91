#pragma once
// Runs a shell command under a fresh Xvfb of its own (window tests). -displayfd lets the server pick
// a free display number itself and write it to fd 3 once it accepts connections, so no number is
// probed that another X server starting at the same moment can take (xvfb-run's choice can).
// Servers started by other processes at once can still collide on a machine running several test
// suites; a display that refuses the command ("Failed to open display") is retried with a fresh
// server after a pause (five tries: once in CI all three quick tries were refused within a second
// while another suite ran). Any other failure is the command's.
#include <filesystem>
#include <string>

namespace tallow::test {

/// True when Xvfb is installed (window tests skip otherwise).
bool xvfbAvailable();

struct XvfbResult {
  int exitCode = -1;
  std::string output;  ///< the command's stdout and stderr (and Xvfb's log when it failed to start)
};

/// Runs `command` (a shell command line; DISPLAY is set for it) in folder `dir` under an
/// 800x600x24 Xvfb.
XvfbResult runUnderXvfb(const std::string& command, const std::filesystem::path& dir);

}  // namespace tallow::test
