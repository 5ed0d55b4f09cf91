#include "gpu/gpu_timer.h"

#include <stdexcept>

namespace tallow::gpu {

void GpuTimer::beginFrame() {
  used_ = 0;
  open_.clear();
}

void GpuTimer::begin(const std::string& pass) {
  if (used_ == pairs_.size()) pairs_.push_back(Pair{});
  Pair& p = pairs_[used_];
  p.name = pass;
  glQueryCounter(p.start.id(), GL_TIMESTAMP);
  open_.push_back(used_++);
}

void GpuTimer::end() {
  if (open_.empty()) throw std::logic_error("GpuTimer::end without begin");
  glQueryCounter(pairs_[open_.back()].stop.id(), GL_TIMESTAMP);
  open_.pop_back();
}

std::vector<PassTiming> GpuTimer::collect() {
  std::vector<PassTiming> out;
  for (std::size_t i = 0; i < used_; ++i) {
    const GLuint64 t0 = pairs_[i].start.result();
    const GLuint64 t1 = pairs_[i].stop.result();
    out.push_back({pairs_[i].name, t1 > t0 ? static_cast<double>(t1 - t0) * 1e-6 : 0.0});
  }
  return out;
}

}  // namespace tallow::gpu
