#pragma once
// A linked GLSL program built from files under shaders/ (see ShaderLibrary), with uniform setters
// that go through glProgramUniform* so that no program binding leaks between passes.
#include <glad/gl.h>
#include <glm/glm.hpp>

#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "gpu/shader_library.h"

namespace tallow::gpu {

struct ShaderStage {
  GLenum type;       ///< GL_VERTEX_SHADER, GL_GEOMETRY_SHADER, GL_FRAGMENT_SHADER, GL_COMPUTE_SHADER, …
  std::string path;  ///< relative to shaders/
};

struct ProgramDesc {
  std::vector<ShaderStage> stages;
  std::vector<std::string> defines = {};                 ///< "NAME VALUE" or "NAME", for every stage
  std::vector<std::string> transformFeedbackVaryings = {};  ///< captured interleaved, if any
};

class Program {
 public:
  Program() = default;
  /// Compiles and links; throws ShaderError (`file:line: message`) on failure.
  Program(const ShaderLibrary& library, const ProgramDesc& desc);
  Program(const Program&) = delete;
  Program& operator=(const Program&) = delete;
  Program(Program&& o) noexcept;
  Program& operator=(Program&& o) noexcept;
  ~Program();

  GLuint id() const { return id_; }
  void use() const { glUseProgram(id_); }

  /// Uniform setters; a name the linker optimised away is silently skipped (location −1).
  void set(std::string_view name, int v);
  void set(std::string_view name, float v);
  void set(std::string_view name, const glm::vec2& v);
  void set(std::string_view name, const glm::vec3& v);
  void set(std::string_view name, const glm::vec4& v);
  void set(std::string_view name, const glm::ivec2& v);
  void set(std::string_view name, const glm::mat3& v);
  void set(std::string_view name, const glm::mat4& v);
  void set(std::string_view name, const glm::mat4* v, int count);
  void set(std::string_view name, const glm::vec3* v, int count);
  void set(std::string_view name, const glm::vec4* v, int count);
  void set(std::string_view name, const float* v, int count);
  void set(std::string_view name, const glm::vec2* v, int count);
  GLint location(std::string_view name);

 private:
  GLuint id_ = 0;
  std::unordered_map<std::string, GLint> locations_;
};

}  // namespace tallow::gpu
