#pragma once
// The failure contract of the command line, as the tests check it: a bad input gets a non-zero
// exit, exactly one line on stderr that starts "tallow: " and names what is wrong, and nothing
// written (shared by the CLI, view and hardening tests).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "support/run_tallow.h"

namespace tallow::test {

/// Files and folders under `dir`, recursively; 0 when `dir` does not exist.
inline int fileCount(const std::filesystem::path& dir) {
  if (!std::filesystem::exists(dir)) return 0;
  int n = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::recursive_directory_iterator(dir)) ++n;
  return n;
}

/// Non-zero exit and exactly one line on stderr, starting "tallow: " and containing `expected`.
inline void expectOneErrorLine(const CommandResult& r, const std::string& expected) {
  EXPECT_NE(r.exitCode, 0);
  EXPECT_EQ(lineCount(r.err), 1) << r.err;
  EXPECT_EQ(r.err.rfind("tallow: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(expected), std::string::npos) << "stderr: " << r.err << "expected: " << expected;
}

/// expectOneErrorLine, and nothing written under `out`.
inline void expectCleanFailure(const CommandResult& r, const std::string& expected, const std::filesystem::path& out) {
  expectOneErrorLine(r, expected);
  EXPECT_EQ(fileCount(out), 0) << "files were written under " << out;
}

}  // namespace tallow::test
