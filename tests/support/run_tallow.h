#pragma once
// Runs the `tallow` executable as a user would, capturing exit status and output.
#include <string>
#include <vector>

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

}  // namespace tallow::test
