#include "sss/bssrdf/bssrdf_gpu.h"

#include <glad/gl.h>

#include <algorithm>
#include <stdexcept>
#include <string>

#include "gpu/gl_objects.h"
#include "gpu/program.h"

namespace tallow::sss {

namespace {

constexpr std::size_t kLocalSize = 64;  // layout(local_size_x) of shaders/bssrdf/probe.comp
/// Configurations per dispatch at most: keeps one dispatch of photon beam diffusion (the slowest
/// model, ~300 kernel evaluations per configuration) well under a second on a GPU.
constexpr std::size_t kDefaultChunk = std::size_t(1) << 16;

/// ProbeConfig of probe.comp: six vec4 (std430).
struct ProbeConfig {
  float xi[4], ni[4], wi[4], xo[4], no[4], material[4];
};
static_assert(sizeof(ProbeConfig) == 6 * 16, "std430 layout of ProbeConfig");

void put(float* d, const glm::dvec3& v) {
  d[0] = static_cast<float>(v.x);
  d[1] = static_cast<float>(v.y);
  d[2] = static_cast<float>(v.z);
  d[3] = 0.0f;
}

ProbeConfig pack(const BssrdfConfig& c) {
  ProbeConfig p;
  put(p.xi, c.xi);
  put(p.ni, c.ni);
  put(p.wi, c.wi);
  put(p.xo, c.xo);
  put(p.no, c.no);
  p.material[0] = static_cast<float>(c.sigma_a);
  p.material[1] = static_cast<float>(c.sigma_s);
  p.material[2] = static_cast<float>(c.g);
  p.material[3] = static_cast<float>(c.eta);
  return p;
}

}  // namespace

std::vector<BssrdfValue> evaluateBssrdfGpu(const gpu::ShaderLibrary& library, BssrdfModel model,
                                           std::span<const BssrdfConfig> configs, bool reciprocal) {
  BssrdfOptions options;
  options.reciprocal = reciprocal;
  return evaluateBssrdfGpu(library, model, configs, options);
}

std::vector<BssrdfValue> evaluateBssrdfGpu(const gpu::ShaderLibrary& library, BssrdfModel model,
                                           std::span<const BssrdfConfig> configs, const BssrdfOptions& options,
                                           std::size_t maxConfigsPerDispatch) {
  std::vector<BssrdfValue> out(configs.size());
  if (configs.empty()) return out;
  if (options.pbdPanelsPerEfold < 1)
    throw std::invalid_argument("pbdPanelsPerEfold must be at least 1 (" + std::to_string(options.pbdPanelsPerEfold) +
                                ")");

  gpu::Program program(library, gpu::ProgramDesc{{{GL_COMPUTE_SHADER, "bssrdf/probe.comp"}}});
  program.set("uModel", static_cast<int>(model));
  program.set("uReciprocal", options.reciprocal ? 1 : 0);
  program.set("uPbdPanelsPerEfold", options.pbdPanelsPerEfold);

  // Chunk size: what one shader storage block may hold, what one dispatch may launch.
  GLint64 maxBlockBytes = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &maxBlockBytes);
  GLint maxGroups = 0;
  glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, 0, &maxGroups);
  std::size_t chunk = std::min({static_cast<std::size_t>(maxBlockBytes) / sizeof(ProbeConfig),
                                static_cast<std::size_t>(maxGroups) * kLocalSize, kDefaultChunk, configs.size()});
  if (maxConfigsPerDispatch > 0) chunk = std::min(chunk, maxConfigsPerDispatch);
  chunk = std::max<std::size_t>(chunk, 1);

  gpu::Buffer input(chunk * sizeof(ProbeConfig));
  gpu::Buffer results(chunk * 2 * sizeof(float));
  std::vector<ProbeConfig> staging(chunk);
  std::vector<float> readBack(2 * chunk);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, input.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, results.id());
  program.use();
  for (std::size_t first = 0; first < configs.size(); first += chunk) {
    const std::size_t count = std::min(chunk, configs.size() - first);
    for (std::size_t i = 0; i < count; ++i) staging[i] = pack(configs[first + i]);
    input.upload(0, count * sizeof(ProbeConfig), staging.data());
    program.set("uCount", static_cast<int>(count));
    glDispatchCompute(static_cast<GLuint>((count + kLocalSize - 1) / kLocalSize), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    results.download(0, count * 2 * sizeof(float), readBack.data());
    for (std::size_t i = 0; i < count; ++i)
      out[first + i] = BssrdfValue{readBack[2 * i], readBack[2 * i + 1]};
  }
  glUseProgram(0);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, 0);
  if (const GLenum error = glGetError(); error != GL_NO_ERROR)
    throw std::runtime_error("evaluateBssrdfGpu: OpenGL error " + std::to_string(error));
  return out;
}

}  // namespace tallow::sss
