#pragma once
// How much memory the current GL context's GPU offers, for the renderer's memory budget
// (sss/memory_budget.h): what the driver reports through GL_NVX_gpu_memory_info (NVIDIA) or
// GL_ATI_meminfo (AMD), else a documented default, and $TALLOW_GPU_MEMORY_MB above both.
#include <cstddef>
#include <string>

#include "gpu/byte_size.h"

namespace tallow::gpu {

/// The budget when the driver reports nothing (Mesa's llvmpipe, Intel): 4 GiB, what the smallest
/// discrete GPUs of the GL 4.5 generation hold, and on llvmpipe a share of system memory a frame
/// can take without pushing a shared 2-core CI machine into swap.
inline constexpr std::size_t kDefaultGpuMemoryBytes = std::size_t{4} << 30;

struct GpuMemory {
  std::size_t bytes = 0;  ///< memory a frame's resources may take
  /// Where the figure comes from, for messages: "GL_NVX_gpu_memory_info", "GL_ATI_meminfo",
  /// "TALLOW_GPU_MEMORY_MB" or "the default where the driver reports none; …".
  std::string source;
};

/// The current context's figure. NVIDIA: GPU_MEMORY_INFO_TOTAL_AVAILABLE_MEMORY_NVX (the memory
/// the driver lets one context use; stable while Tallow allocates, unlike the current-free figure).
/// AMD: TEXTURE_FREE_MEMORY_ATI, free memory, read once per process (the first query, before
/// Tallow's own allocations lower it). $TALLOW_GPU_MEMORY_MB (a positive integer) overrides both:
/// for drivers that report nothing and for tests. Throws std::invalid_argument (one line) when
/// that variable is not a positive integer.
GpuMemory gpuMemory();

}  // namespace tallow::gpu
