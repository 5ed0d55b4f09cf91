#pragma once
// The GPU side of sss.maps=auto (sss/maps/map_count.h): a ring of small storage buffers that
// Algorithm 1's callers count coverage into (shaders/maps/coverage_counts.glsl, binding kBinding),
// each read back once a fence says the GPU has finished its frame, so that no frame waits for the
// GPU (the decision lags a frame or two). When every buffer of the ring is still in flight, the
// frame counts nothing.
#include <array>
#include <cstdint>
#include <optional>

#include "gpu/gl_objects.h"
#include "sss/maps/map_count.h"

namespace tallow::sss {

class MapCoverageProbe {
 public:
  static constexpr GLuint kBinding = 9;  ///< shaders/maps/algorithm1.glsl's MapCoverageCounts
  static constexpr std::size_t kRing = 3;

  /// Before the frame's passes: zeroes a free buffer and binds it at kBinding. False (nothing bound)
  /// when all of them still wait for the GPU.
  bool begin(int maps);
  /// After the frame's passes: the fence behind them; unbinds the buffer.
  void end();
  /// The newest counts the GPU has finished, without waiting; older finished ones are dropped.
  std::optional<MapCoverageCounts> poll();
  /// Drops the counts still in flight (Renderer::invalidate: nothing from before reaches the chooser).
  void forget();

 private:
  struct Slot {
    gpu::Buffer buffer;
    gpu::Fence fence;
    int maps = 0;
    std::uint64_t frame = 0;
  };
  std::array<Slot, kRing> ring_;
  int current_ = -1;
  std::uint64_t frames_ = 0;
};

}  // namespace tallow::sss
