#include "sss/maps/map_coverage_probe.h"

#include <vector>

namespace tallow::sss {
namespace {

constexpr std::size_t kWords = static_cast<std::size_t>(glsl::COVERAGE_HISTOGRAMS * glsl::COVERAGE_HISTOGRAM_SIZE);

CoverageHistogram histogram(const std::vector<std::uint32_t>& words, int index) {
  CoverageHistogram h;
  const std::size_t base = static_cast<std::size_t>(index * glsl::COVERAGE_HISTOGRAM_SIZE);
  for (std::size_t k = 0; k < h.first.size(); ++k) h.first[k] = words[base + k];
  h.unseen = words[base + static_cast<std::size_t>(glsl::COVERAGE_MAX_MAPS)];
  return h;
}

}  // namespace

bool MapCoverageProbe::begin(int maps) {
  current_ = -1;
  for (std::size_t i = 0; i < kRing; ++i)
    if (ring_[i].fence.empty()) {
      current_ = static_cast<int>(i);
      break;
    }
  if (current_ < 0) return false;
  Slot& s = ring_[static_cast<std::size_t>(current_)];
  if (s.buffer.size() == 0) s.buffer = gpu::Buffer(kWords * sizeof(std::uint32_t));
  glClearNamedBufferData(s.buffer.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBinding, s.buffer.id());
  s.maps = maps;
  s.frame = ++frames_;
  return true;
}

void MapCoverageProbe::end() {
  if (current_ < 0) return;
  // The counters were written with atomics by fragment and compute shaders: make them visible to
  // the read-back that follows the fence.
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  ring_[static_cast<std::size_t>(current_)].fence = gpu::Fence::insert();
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBinding, 0);
  current_ = -1;
}

void MapCoverageProbe::forget() {
  for (Slot& s : ring_) s.fence = gpu::Fence();
  current_ = -1;
}

std::optional<MapCoverageCounts> MapCoverageProbe::poll() {
  Slot* newest = nullptr;
  for (Slot& s : ring_) {
    if (s.fence.empty() || !s.fence.signaled()) continue;
    if (newest && newest->frame > s.frame) {
      s.fence = gpu::Fence();
      continue;
    }
    if (newest) newest->fence = gpu::Fence();
    newest = &s;
  }
  if (!newest) return std::nullopt;
  std::vector<std::uint32_t> words(kWords);
  newest->buffer.download(0, kWords * sizeof(std::uint32_t), words.data());
  newest->fence = gpu::Fence();
  MapCoverageCounts c;
  c.maps = newest->maps;
  c.camera = histogram(words, glsl::COVERAGE_CAMERA);
  c.cameraFacing = histogram(words, glsl::COVERAGE_CAMERA_FACING);
  CoverageHistogram vpls = histogram(words, glsl::COVERAGE_VPLS);
  if (vpls.total(c.maps) > 0) c.vpls = vpls;
  return c;
}

}  // namespace tallow::sss
