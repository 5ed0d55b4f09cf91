#pragma once
// The BSSRDF models evaluated by the GPU: shaders/bssrdf/probe.comp runs the shared model files
// (the same lines as sss/bssrdf/bssrdf.h evaluates on the CPU) on a batch of configurations, in float.
#include <cstddef>
#include <span>
#include <vector>

#include "gpu/shader_library.h"
#include "sss/bssrdf/bssrdf.h"

namespace tallow::sss {

/// Evaluates every configuration on the GPU; needs a current OpenGL 4.5 context. The inputs are
/// converted to float. Large batches are processed in chunks that respect
/// GL_MAX_SHADER_STORAGE_BLOCK_SIZE and GL_MAX_COMPUTE_WORK_GROUP_COUNT. Throws gpu::ShaderError
/// when the shader does not compile, std::runtime_error on a GL error.
std::vector<BssrdfValue> evaluateBssrdfGpu(const gpu::ShaderLibrary& library, BssrdfModel model,
                                           std::span<const BssrdfConfig> configs, bool reciprocal = false);

/// The same with options; `maxConfigsPerDispatch` > 0 lowers the chunk size (tests use it to
/// exercise the chunking).
std::vector<BssrdfValue> evaluateBssrdfGpu(const gpu::ShaderLibrary& library, BssrdfModel model,
                                           std::span<const BssrdfConfig> configs, const BssrdfOptions& options,
                                           std::size_t maxConfigsPerDispatch = 0);

}  // namespace tallow::sss
