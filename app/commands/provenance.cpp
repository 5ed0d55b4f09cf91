#include "app/commands/provenance.h"

#include <chrono>
#include <ctime>
#include <fstream>
#include <optional>
#include <thread>
#include <vector>

#include "gpu/gl_limits.h"
#include "tallow_version.h"

namespace tallow::app {
namespace {

struct Recorded {
  std::vector<std::string> words;
  std::optional<std::chrono::system_clock::time_point> start;
};

Recorded& recorded() {
  static Recorded r;
  return r;
}

/// `word` as a POSIX shell reads it back: bare when it holds only safe characters, else in single
/// quotes (a quote inside as '\'').
std::string shellWord(const std::string& word) {
  const bool bare = !word.empty() && word.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                                           "0123456789-_./=:,+@%") == std::string::npos;
  if (bare) return word;
  std::string quoted = "'";
  for (const char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

}  // namespace

void recordCommandLine(int argc, const char* const* argv) {
  Recorded& r = recorded();
  r.words.assign(argv, argv + argc);
  r.start = std::chrono::system_clock::now();
}

std::string commandLine() {
  std::string line;
  for (const std::string& w : recorded().words) {
    if (!line.empty()) line += ' ';
    line += shellWord(w);
  }
  return line;
}

std::string tallowVersion() { return std::string(TALLOW_VERSION) + " (git " + TALLOW_GIT_DESCRIBE + ")"; }

std::string gitCommit() { return TALLOW_GIT_COMMIT; }

std::string runStartUtc() {
  const auto start = recorded().start.value_or(std::chrono::system_clock::now());
  const std::time_t t = std::chrono::system_clock::to_time_t(start);
  std::tm utc{};
  gmtime_r(&t, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

std::string cpuModel() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      const auto start = colon == std::string::npos ? std::string::npos : line.find_first_not_of(' ', colon + 1);
      if (start != std::string::npos) return line.substr(start);
    }
  return "unknown";
}

nlohmann::json provenanceJson() {
  return {{"tallow_version", tallowVersion()},
          {"git_commit", gitCommit()},
          {"command_line", commandLine()},
          {"date", runStartUtc()},
          {"cpu", {{"model", cpuModel()}, {"hardware_threads", std::thread::hardware_concurrency()}}}};
}

nlohmann::json glJson(gpu::GlBackend backend, const gpu::GlInfo& info) {
  return {{"backend", std::string(gpu::glBackendName(backend))},
          {"GL_VENDOR", info.vendor},
          {"GL_RENDERER", info.renderer},
          {"GL_VERSION", info.version},
          {"GL_SHADING_LANGUAGE_VERSION", info.glsl}};
}

nlohmann::json glLimitsJson() {
  // What decides which path a pass takes on this driver (issue 39): dual contouring's geometry
  // shader emits up to 54 vertices, the layered passes write gl_Layer from the vertex shader where
  // the extension is offered, and per-pass invocation counts need the statistics queries.
  const gpu::GlLimits& l = gpu::glLimits();
  return {{"GL_MAX_GEOMETRY_OUTPUT_VERTICES", l.maxGeometryOutputVertices},
          {"GL_MAX_TRANSFORM_FEEDBACK_BUFFERS", l.maxTransformFeedbackBuffers},
          {"GL_MAX_TEXTURE_SIZE", l.maxTextureSize},
          {"GL_MAX_ARRAY_TEXTURE_LAYERS", l.maxArrayTextureLayers},
          {"GL_ARB_shader_viewport_layer_array", l.layerInVertexShader},
          {"GL_ARB_pipeline_statistics_query", l.pipelineStatistics}};
}

nlohmann::json glJson(const gpu::GlContext& context) {
  nlohmann::json out = glJson(context.backend(), context.info());
  out["limits"] = glLimitsJson();
  return out;
}

}  // namespace tallow::app
