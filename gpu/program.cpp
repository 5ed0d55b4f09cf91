#include "gpu/program.h"

#include <glm/gtc/type_ptr.hpp>

#include <utility>

namespace tallow::gpu {
namespace {

std::string infoLog(GLuint object, bool isProgram) {
  GLint length = 0;
  if (isProgram) glGetProgramiv(object, GL_INFO_LOG_LENGTH, &length);
  else glGetShaderiv(object, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<std::size_t>(length > 0 ? length : 1), '\0');
  if (isProgram) glGetProgramInfoLog(object, length, nullptr, log.data());
  else glGetShaderInfoLog(object, length, nullptr, log.data());
  while (!log.empty() && (log.back() == '\0' || log.back() == '\n')) log.pop_back();
  return log;
}

/// The first line of a mapped log that reports an error (falls back to the first line).
std::string firstError(const std::string& mapped, const std::string& fallback) {
  std::string first;
  std::size_t start = 0;
  while (start < mapped.size()) {
    const std::size_t end = mapped.find('\n', start);
    const std::string line = mapped.substr(start, end - start);
    if (first.empty()) first = line;
    if (line.find("error") != std::string::npos) return line;
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return first.empty() ? fallback : first;
}

}  // namespace

Program::Program(const ShaderLibrary& library, const ProgramDesc& desc) {
  id_ = glCreateProgram();
  std::vector<GLuint> shaders;
  auto cleanup = [&] {
    for (GLuint s : shaders) glDeleteShader(s);
  };
  for (const ShaderStage& stage : desc.stages) {
    ExpandedSource source;
    try {
      source = library.expand(stage.path, desc.defines);
    } catch (...) {
      cleanup();
      glDeleteProgram(std::exchange(id_, 0));
      throw;
    }
    const GLuint shader = glCreateShader(stage.type);
    shaders.push_back(shader);
    const char* text = source.text.c_str();
    glShaderSource(shader, 1, &text, nullptr);
    glCompileShader(shader);
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
      const std::string mapped = mapShaderLog(infoLog(shader, false), source);
      cleanup();
      glDeleteProgram(std::exchange(id_, 0));
      throw ShaderError(firstError(mapped, "shaders/" + stage.path + ": compile failed"), mapped);
    }
    glAttachShader(id_, shader);
  }
  if (!desc.transformFeedbackVaryings.empty()) {
    std::vector<const char*> names;
    for (const auto& v : desc.transformFeedbackVaryings) names.push_back(v.c_str());
    glTransformFeedbackVaryings(id_, static_cast<GLsizei>(names.size()), names.data(), GL_INTERLEAVED_ATTRIBS);
  }
  glLinkProgram(id_);
  cleanup();
  GLint linked = GL_FALSE;
  glGetProgramiv(id_, GL_LINK_STATUS, &linked);
  if (!linked) {
    const std::string log = infoLog(id_, true);
    std::string files;
    for (const ShaderStage& s : desc.stages) files += (files.empty() ? "" : " + ") + ("shaders/" + s.path);
    glDeleteProgram(std::exchange(id_, 0));
    throw ShaderError(files + ": link failed: " + firstError(log, "?"), log);
  }
}

Program::Program(Program&& o) noexcept : id_(std::exchange(o.id_, 0)), locations_(std::move(o.locations_)) {}

Program& Program::operator=(Program&& o) noexcept {
  if (this != &o) {
    if (id_) glDeleteProgram(id_);
    id_ = std::exchange(o.id_, 0);
    locations_ = std::move(o.locations_);
  }
  return *this;
}

Program::~Program() {
  if (id_) glDeleteProgram(id_);
}

GLint Program::location(std::string_view name) {
  const std::string key(name);
  auto it = locations_.find(key);
  if (it != locations_.end()) return it->second;
  const GLint loc = glGetUniformLocation(id_, key.c_str());
  locations_.emplace(key, loc);
  return loc;
}

void Program::set(std::string_view n, int v) { glProgramUniform1i(id_, location(n), v); }
void Program::set(std::string_view n, float v) { glProgramUniform1f(id_, location(n), v); }
void Program::set(std::string_view n, const glm::vec2& v) { glProgramUniform2fv(id_, location(n), 1, glm::value_ptr(v)); }
void Program::set(std::string_view n, const glm::vec3& v) { glProgramUniform3fv(id_, location(n), 1, glm::value_ptr(v)); }
void Program::set(std::string_view n, const glm::vec4& v) { glProgramUniform4fv(id_, location(n), 1, glm::value_ptr(v)); }
void Program::set(std::string_view n, const glm::ivec2& v) { glProgramUniform2iv(id_, location(n), 1, glm::value_ptr(v)); }
void Program::set(std::string_view n, const glm::mat3& v) {
  glProgramUniformMatrix3fv(id_, location(n), 1, GL_FALSE, glm::value_ptr(v));
}
void Program::set(std::string_view n, const glm::mat4& v) {
  glProgramUniformMatrix4fv(id_, location(n), 1, GL_FALSE, glm::value_ptr(v));
}
void Program::set(std::string_view n, const glm::mat4* v, int count) {
  glProgramUniformMatrix4fv(id_, location(n), count, GL_FALSE, glm::value_ptr(v[0]));
}
void Program::set(std::string_view n, const glm::vec3* v, int count) {
  glProgramUniform3fv(id_, location(n), count, glm::value_ptr(v[0]));
}
void Program::set(std::string_view n, const glm::vec4* v, int count) {
  glProgramUniform4fv(id_, location(n), count, glm::value_ptr(v[0]));
}
void Program::set(std::string_view n, const float* v, int count) { glProgramUniform1fv(id_, location(n), count, v); }
void Program::set(std::string_view n, const glm::vec2* v, int count) {
  glProgramUniform2fv(id_, location(n), count, glm::value_ptr(v[0]));
}

}  // namespace tallow::gpu
