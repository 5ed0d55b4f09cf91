#pragma once
// Where an output came from, for stats.json, bench.json and the reference's EXR metadata: Tallow's
// version (the git checkout at build time, cmake/Version.cmake), the command line as given, when
// the run started (UTC), and the CPU. The GL strings come with the context (frame_stats.h).
#include <nlohmann/json.hpp>

#include "gpu/gl_context.h"

#include <string>

namespace tallow::app {

/// Remembers argv and the start time (main calls it first).
void recordCommandLine(int argc, const char* const* argv);
/// The words of the command line, each quoted for a POSIX shell when it needs to be, so that the
/// line can be pasted back: `tallow capture --set 'material=White Grapefruit Juice' --out o`.
/// "" before recordCommandLine.
std::string commandLine();
/// "0.1 (git 1a2b3c4d5e6f-dirty)": the project version and `git describe` at build time.
std::string tallowVersion();
/// The full commit hash at build time ("unknown" outside a git checkout).
std::string gitCommit();
/// The run's start (recordCommandLine, else now) as ISO 8601 UTC: "2024-05-01T12:34:56Z".
std::string runStartUtc();
/// /proc/cpuinfo's first "model name" ("unknown" elsewhere).
std::string cpuModel();

/// {"tallow_version", "git_commit", "command_line", "date", "cpu": {"model", "hardware_threads"}}.
nlohmann::json provenanceJson();
/// The GL context an output was measured with: {"backend", "GL_VENDOR", "GL_RENDERER", "GL_VERSION",
/// "GL_SHADING_LANGUAGE_VERSION"} (stats.json, bench.json and the probes' reports).
nlohmann::json glJson(gpu::GlBackend backend, const gpu::GlInfo& info);
/// glJson of the context, with "limits": glLimitsJson().
nlohmann::json glJson(const gpu::GlContext& context);
/// The current context's limits that pick a pass's path (gpu::glLimits): the largest geometry-shader
/// output, transform-feedback buffers, texture sizes, the viewport-layer and statistics extensions.
nlohmann::json glLimitsJson();

}  // namespace tallow::app
