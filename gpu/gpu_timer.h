#pragma once
// GPU time per named pass, from GL_TIMESTAMP query pairs (pairs, not GL_TIME_ELAPSED, so that
// passes may nest), kept in a ring of frames so that a frame never waits for its own queries: the
// times of frame n are read once the GPU has them, typically a frame or two later, or right away
// after a glFinish (capture, bench). A frame whose times are never read is dropped when the ring
// comes round to its slot again.
#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "gpu/gl_objects.h"

namespace tallow::gpu {

struct PassTiming {
  std::string name;
  double gpuMs = std::numeric_limits<double>::quiet_NaN();  ///< NaN until the GPU's times are read
  double cpuMs = 0.0;  ///< the CPU clock's time in the pass (its own work and the commands it issued)
  /// CPU time the rendering thread itself used in the pass (CLOCK_THREAD_CPUTIME_ID): Tallow's work
  /// and the driver's on that thread, not time spent waiting. A software rasteriser's worker threads
  /// (llvmpipe runs a compute dispatch on them while the caller waits) are not in it; cpuMs has the wait.
  double threadCpuMs = 0.0;
};

class GpuTimer {
 public:
  /// Frames whose times can still be read; a GPU is rarely more than two or three frames behind.
  static constexpr std::size_t kRing = 4;

  /// Starts the next frame (numbered 1, 2, …) and returns its number.
  std::uint64_t beginFrame();
  void begin(const std::string& pass);
  void end();
  /// The GPU milliseconds of `frame`'s passes, in the order they began. With wait = false only when
  /// the GPU has finished all of them (never stalls); with wait = true it waits for them. nullopt
  /// when not available yet (wait = false) or no longer kept (the ring reused the frame's slot).
  std::optional<std::vector<double>> times(std::uint64_t frame, bool wait) const;

 private:
  struct Pair {
    std::string name;
    Query start{GL_TIMESTAMP}, stop{GL_TIMESTAMP};
  };
  struct Slot {
    std::uint64_t frame = 0;  ///< 0: empty
    std::vector<Pair> pairs;  ///< a pool; the first `used` belong to `frame`
    std::size_t used = 0;
  };
  Slot& slot(std::uint64_t frame) { return slots_[frame % kRing]; }
  const Slot& slot(std::uint64_t frame) const { return slots_[frame % kRing]; }

  std::array<Slot, kRing> slots_;
  std::uint64_t frame_ = 0;
  std::vector<std::size_t> open_;
};

/// Times a scope: `GpuScope s(timer, "shadow");`.
class GpuScope {
 public:
  GpuScope(GpuTimer& timer, const std::string& pass) : timer_(timer) { timer_.begin(pass); }
  ~GpuScope() { timer_.end(); }
  GpuScope(const GpuScope&) = delete;
  GpuScope& operator=(const GpuScope&) = delete;

 private:
  GpuTimer& timer_;
};

}  // namespace tallow::gpu
