#pragma once
// GPU time per named pass, from GL_TIMESTAMP query pairs (pairs, not GL_TIME_ELAPSED, so that
// passes may nest). A frame's timings are read after it is submitted; reading waits for the GPU.
#include <string>
#include <vector>

#include "gpu/gl_objects.h"

namespace tallow::gpu {

struct PassTiming {
  std::string name;
  double gpuMs = 0.0;
};

class GpuTimer {
 public:
  void beginFrame();
  void begin(const std::string& pass);
  void end();
  /// Waits for this frame's queries; passes in the order they began.
  std::vector<PassTiming> collect();

 private:
  struct Pair {
    std::string name;
    Query start{GL_TIMESTAMP}, stop{GL_TIMESTAMP};
  };
  std::vector<Pair> pairs_;  ///< a pool; the first `used_` belong to the current frame
  std::vector<std::size_t> open_;
  std::size_t used_ = 0;
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
