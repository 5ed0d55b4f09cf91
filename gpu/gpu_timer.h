#pragma once
// GPU time per named pass, from GL_TIMESTAMP query pairs (pairs, not GL_TIME_ELAPSED, so that
// passes may nest), kept in a ring of frames so that a frame never waits for its own queries: the
// times of frame n are read once the GPU has them, typically a frame or two later, or right away
// after a glFinish (capture, bench). A frame whose times are never read is dropped when the ring
// comes round to its slot again.
//
// Where the driver offers GL_ARB_pipeline_statistics_query the same passes are counted: shader
// invocations per stage and primitives (issue 39, point 6: what a cost model turns into time on a
// GPU we do not have, docs/device-bench.md). A statistics query cannot nest, so the counters run
// per segment — the stretch between two begin/end calls, charged to the innermost open pass — and a
// pass's counts add its nested passes' segments, as its time includes theirs.
#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "gpu/gl_objects.h"

namespace tallow::gpu {

/// A pass's pipeline statistics, as the driver counts them.
struct PipelineCounts {
  std::uint64_t vertex = 0;      ///< GL_VERTEX_SHADER_INVOCATIONS
  std::uint64_t geometry = 0;    ///< GL_GEOMETRY_SHADER_INVOCATIONS
  std::uint64_t primitives = 0;  ///< GL_CLIPPING_INPUT_PRIMITIVES: primitives that reach the rasteriser
  std::uint64_t fragment = 0;    ///< GL_FRAGMENT_SHADER_INVOCATIONS
  std::uint64_t compute = 0;     ///< GL_COMPUTE_SHADER_INVOCATIONS
  PipelineCounts& operator+=(const PipelineCounts& o);
  bool operator==(const PipelineCounts&) const = default;
};

struct PassTiming {
  std::string name;
  double gpuMs = std::numeric_limits<double>::quiet_NaN();  ///< NaN until the GPU's times are read
  double cpuMs = 0.0;  ///< the CPU clock's time in the pass (its own work and the commands it issued)
  /// CPU time the rendering thread itself used in the pass (CLOCK_THREAD_CPUTIME_ID): Tallow's work
  /// and the driver's on that thread, not time spent waiting. A software rasteriser's worker threads
  /// (llvmpipe runs a compute dispatch on them while the caller waits) are not in it; cpuMs has the wait.
  double threadCpuMs = 0.0;
  /// The pass's pipeline statistics: none until read, or where the driver cannot count them.
  std::optional<PipelineCounts> counts;
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
  /// Pipeline statistics (when counted) are waited for, or looked at, with the times.
  std::optional<std::vector<double>> times(std::uint64_t frame, bool wait) const;
  /// The pipeline statistics of `frame`'s passes, in the same order, each with its nested passes'
  /// counts; as times(), and nullopt where the driver has no GL_ARB_pipeline_statistics_query.
  std::optional<std::vector<PipelineCounts>> counts(std::uint64_t frame, bool wait) const;

 private:
  static constexpr std::size_t kNoPass = static_cast<std::size_t>(-1);
  struct Pair {
    std::string name;
    std::size_t parent = kNoPass;  ///< the pass it is nested in
    Query start{GL_TIMESTAMP}, stop{GL_TIMESTAMP};
  };
  /// One query per counter, running while `pass` is the innermost open pass.
  struct Segment {
    std::size_t pass = 0;
    std::array<Query, 5> queries;
  };
  struct Slot {
    std::uint64_t frame = 0;  ///< 0: empty
    std::vector<Pair> pairs;  ///< a pool; the first `used` belong to `frame`
    std::size_t used = 0;
    std::vector<Segment> segments;  ///< a pool likewise; the first `segmentsUsed` belong to `frame`
    std::size_t segmentsUsed = 0;
  };
  bool available(const Slot& s) const;
  /// available(s), after a glFinish if `wait` and it was not.
  bool ready(const Slot& s, bool wait) const;
  void openSegment(std::size_t pass);
  void closeSegment();
  Slot& slot(std::uint64_t frame) { return slots_[frame % kRing]; }
  const Slot& slot(std::uint64_t frame) const { return slots_[frame % kRing]; }

  std::array<Slot, kRing> slots_;
  std::uint64_t frame_ = 0;
  std::vector<std::size_t> open_;
  bool statistics_ = false;   ///< the driver counts (decided at the first frame)
  bool segmentOpen_ = false;
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
