#include "gpu/gpu_memory.h"

#include <glad/gl.h>

#include <charconv>
#include <cstdlib>
#include <stdexcept>
#include <string_view>

namespace tallow::gpu {
namespace {

constexpr std::size_t kKiB = 1024;
constexpr std::size_t kMiB = std::size_t{1} << 20;
/// Upper bound of $TALLOW_GPU_MEMORY_MB (1 PiB): no GPU holds more, so a larger figure is a typo.
constexpr std::size_t kMaxOverrideMb = std::size_t{1} << 30;

}  // namespace

GpuMemory gpuMemory() {
  if (const char* text = std::getenv("TALLOW_GPU_MEMORY_MB"); text && *text) {
    const std::string_view s(text);
    std::size_t mb = 0;
    const auto r = std::from_chars(s.data(), s.data() + s.size(), mb);
    if (r.ec != std::errc() || r.ptr != s.data() + s.size() || mb == 0 || mb > kMaxOverrideMb)
      throw std::invalid_argument("TALLOW_GPU_MEMORY_MB: expected a positive number of MiB, got \"" + std::string(s) +
                                  "\"");
    return {mb * kMiB, "TALLOW_GPU_MEMORY_MB"};
  }
  if (GLAD_GL_NVX_gpu_memory_info) {
    GLint kib = 0;
    glGetIntegerv(GL_GPU_MEMORY_INFO_TOTAL_AVAILABLE_MEMORY_NVX, &kib);
    if (kib > 0) return {static_cast<std::size_t>(kib) * kKiB, "GL_NVX_gpu_memory_info"};
  }
  if (GLAD_GL_ATI_meminfo) {
    // Free memory falls as Tallow allocates, so the first reading stands for the whole run.
    static const std::size_t firstFree = [] {
      GLint info[4] = {0, 0, 0, 0};  // total free, largest free block, auxiliary total, auxiliary largest (KiB)
      glGetIntegerv(GL_TEXTURE_FREE_MEMORY_ATI, info);
      return static_cast<std::size_t>(info[0] > 0 ? info[0] : 0) * kKiB;
    }();
    if (firstFree > 0) return {firstFree, "GL_ATI_meminfo"};
  }
  return {kDefaultGpuMemoryBytes, "the default where the driver reports none; TALLOW_GPU_MEMORY_MB sets it"};
}

}  // namespace tallow::gpu
