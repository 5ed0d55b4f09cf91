#include "gpu/gpu_timer.h"

#include <stdexcept>

namespace tallow::gpu {

std::uint64_t GpuTimer::beginFrame() {
  if (!open_.empty()) throw std::logic_error("GpuTimer::beginFrame with a pass still open");
  ++frame_;
  Slot& s = slot(frame_);
  s.frame = frame_;  // the frame kRing before, if never read, is dropped: its queries are reused
  s.used = 0;
  return frame_;
}

void GpuTimer::begin(const std::string& pass) {
  if (frame_ == 0) throw std::logic_error("GpuTimer::begin before beginFrame");
  Slot& s = slot(frame_);
  if (s.used == s.pairs.size()) s.pairs.push_back(Pair{});
  Pair& p = s.pairs[s.used];
  p.name = pass;
  glQueryCounter(p.start.id(), GL_TIMESTAMP);
  open_.push_back(s.used++);
}

void GpuTimer::end() {
  if (open_.empty()) throw std::logic_error("GpuTimer::end without begin");
  glQueryCounter(slot(frame_).pairs[open_.back()].stop.id(), GL_TIMESTAMP);
  open_.pop_back();
}

std::optional<std::vector<double>> GpuTimer::times(std::uint64_t frame, bool wait) const {
  if (frame == 0 || frame > frame_) return std::nullopt;
  const Slot& s = slot(frame);
  if (s.frame != frame) return std::nullopt;          // reused by a later frame
  if (frame == frame_ && !open_.empty()) return std::nullopt;  // still being recorded
  if (!wait)
    for (std::size_t i = s.used; i-- > 0;)
      if (!s.pairs[i].stop.resultAvailable() || !s.pairs[i].start.resultAvailable()) return std::nullopt;
  std::vector<double> ms;
  ms.reserve(s.used);
  for (std::size_t i = 0; i < s.used; ++i) {
    const GLuint64 t0 = s.pairs[i].start.result();
    const GLuint64 t1 = s.pairs[i].stop.result();
    ms.push_back(t1 > t0 ? static_cast<double>(t1 - t0) * 1e-6 : 0.0);
  }
  return ms;
}

}  // namespace tallow::gpu
