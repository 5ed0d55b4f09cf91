#pragma once
// Shader sources: the files under shaders/, embedded at build time or read from an override folder
// (--shader-dir, for live editing). Expands `#include "path"` (relative to shaders/, each file at
// most once per stage) and `#include NAME` where a define gives NAME a quoted path (a variant that
// includes its own file), prepends `#define`s after `#version`, and maps the driver's error log
// back to `file:line: message`.
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace tallow::gpu {

/// A shader failed to compile or link. what() is the first error as `file:line: message`;
/// log() holds every line of the driver's log, mapped the same way.
class ShaderError : public std::runtime_error {
 public:
  ShaderError(const std::string& first, std::string log) : std::runtime_error(first), log_(std::move(log)) {}
  const std::string& log() const { return log_; }

 private:
  std::string log_;
};

struct ExpandedSource {
  std::string text;                ///< ready for glShaderSource
  std::vector<std::string> files;  ///< source-string number (as in `#line L N`) → file path
};

class ShaderLibrary {
 public:
  /// Sources come from the embedded copy, or from `overrideDir` when given.
  explicit ShaderLibrary(std::optional<std::filesystem::path> overrideDir = std::nullopt);

  /// The text of `path` (relative to shaders/). Throws ShaderError when there is no such file.
  std::string read(std::string_view path) const;
  /// Expands includes and inserts `#define NAME VALUE` lines (given as "NAME VALUE" or "NAME").
  ExpandedSource expand(std::string_view path, const std::vector<std::string>& defines = {}) const;
  const std::optional<std::filesystem::path>& overrideDir() const { return overrideDir_; }

 private:
  void expandInto(std::string_view path, ExpandedSource& out, std::vector<std::string>& stack,
                  std::vector<std::string>& seen, const std::vector<std::string>& defines) const;
  std::optional<std::filesystem::path> overrideDir_;
};

/// Rewrites a driver's info log (Mesa `0:12(5): error: …`, NVIDIA `0(12) : error C0000: …`) so that
/// each line names the file and line of `source` it refers to.
std::string mapShaderLog(const std::string& log, const ExpandedSource& source);

}  // namespace tallow::gpu
