#include "gpu/gpu_timer.h"

#include <stdexcept>

#include "gpu/gl_limits.h"

namespace tallow::gpu {
namespace {

// The counters in PipelineCounts' order (GL_ARB_pipeline_statistics_query's targets).
constexpr std::array<GLenum, 5> kCounterTargets = {GL_VERTEX_SHADER_INVOCATIONS_ARB, GL_GEOMETRY_SHADER_INVOCATIONS,
                                                   GL_CLIPPING_INPUT_PRIMITIVES_ARB,
                                                   GL_FRAGMENT_SHADER_INVOCATIONS_ARB,
                                                   GL_COMPUTE_SHADER_INVOCATIONS_ARB};

}  // namespace

PipelineCounts& PipelineCounts::operator+=(const PipelineCounts& o) {
  vertex += o.vertex;
  geometry += o.geometry;
  primitives += o.primitives;
  fragment += o.fragment;
  compute += o.compute;
  return *this;
}

std::uint64_t GpuTimer::beginFrame() {
  if (!open_.empty()) throw std::logic_error("GpuTimer::beginFrame with a pass still open");
  if (frame_ == 0) statistics_ = glLimits().pipelineStatistics;
  ++frame_;
  Slot& s = slot(frame_);
  s.frame = frame_;  // the frame kRing before, if never read, is dropped: its queries are reused
  s.used = 0;
  s.segmentsUsed = 0;
  return frame_;
}

void GpuTimer::openSegment(std::size_t pass) {
  if (!statistics_) return;
  Slot& s = slot(frame_);
  if (s.segmentsUsed == s.segments.size()) {
    Segment fresh;
    for (std::size_t c = 0; c < kCounterTargets.size(); ++c) fresh.queries[c] = Query(kCounterTargets[c]);
    s.segments.push_back(std::move(fresh));
  }
  Segment& segment = s.segments[s.segmentsUsed++];
  segment.pass = pass;
  for (std::size_t c = 0; c < kCounterTargets.size(); ++c) glBeginQuery(kCounterTargets[c], segment.queries[c].id());
  segmentOpen_ = true;
}

void GpuTimer::closeSegment() {
  if (!segmentOpen_) return;
  for (GLenum target : kCounterTargets) glEndQuery(target);
  segmentOpen_ = false;
}

void GpuTimer::begin(const std::string& pass) {
  if (frame_ == 0) throw std::logic_error("GpuTimer::begin before beginFrame");
  closeSegment();
  Slot& s = slot(frame_);
  if (s.used == s.pairs.size()) s.pairs.push_back(Pair{});
  Pair& p = s.pairs[s.used];
  p.name = pass;
  p.parent = open_.empty() ? kNoPass : open_.back();
  glQueryCounter(p.start.id(), GL_TIMESTAMP);
  open_.push_back(s.used++);
  openSegment(open_.back());
}

void GpuTimer::end() {
  if (open_.empty()) throw std::logic_error("GpuTimer::end without begin");
  closeSegment();
  glQueryCounter(slot(frame_).pairs[open_.back()].stop.id(), GL_TIMESTAMP);
  open_.pop_back();
  if (!open_.empty()) openSegment(open_.back());
}

bool GpuTimer::available(const Slot& s) const {
  for (std::size_t i = s.used; i-- > 0;)
    if (!s.pairs[i].stop.resultAvailable() || !s.pairs[i].start.resultAvailable()) return false;
  for (std::size_t i = s.segmentsUsed; i-- > 0;)
    for (const Query& q : s.segments[i].queries)
      if (!q.resultAvailable()) return false;
  return true;
}

bool GpuTimer::ready(const Slot& s, bool wait) const {
  if (available(s)) return true;
  if (!wait) return false;
  // Every result is asked for before it is read (issue 39): waiting means finishing the GPU's work,
  // after which the queries have their results.
  glFinish();
  return available(s);
}

std::optional<std::vector<double>> GpuTimer::times(std::uint64_t frame, bool wait) const {
  if (frame == 0 || frame > frame_) return std::nullopt;
  const Slot& s = slot(frame);
  if (s.frame != frame) return std::nullopt;          // reused by a later frame
  if (frame == frame_ && !open_.empty()) return std::nullopt;  // still being recorded
  if (!ready(s, wait)) return std::nullopt;
  std::vector<double> ms;
  ms.reserve(s.used);
  for (std::size_t i = 0; i < s.used; ++i) {
    const GLuint64 t0 = s.pairs[i].start.result();
    const GLuint64 t1 = s.pairs[i].stop.result();
    ms.push_back(t1 > t0 ? static_cast<double>(t1 - t0) * 1e-6 : 0.0);
  }
  return ms;
}

std::optional<std::vector<PipelineCounts>> GpuTimer::counts(std::uint64_t frame, bool wait) const {
  if (!statistics_ || frame == 0 || frame > frame_) return std::nullopt;
  const Slot& s = slot(frame);
  if (s.frame != frame) return std::nullopt;
  if (frame == frame_ && !open_.empty()) return std::nullopt;
  if (!ready(s, wait)) return std::nullopt;
  std::vector<PipelineCounts> out(s.used);
  for (std::size_t i = 0; i < s.segmentsUsed; ++i) {
    const Segment& segment = s.segments[i];
    PipelineCounts c;
    c.vertex = segment.queries[0].result();
    c.geometry = segment.queries[1].result();
    c.primitives = segment.queries[2].result();
    c.fragment = segment.queries[3].result();
    c.compute = segment.queries[4].result();
    for (std::size_t pass = segment.pass; pass != kNoPass; pass = s.pairs[pass].parent) out[pass] += c;  // nested: ancestors too
  }
  return out;
}

}  // namespace tallow::gpu
