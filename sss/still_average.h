#pragma once
// render.aa: anti-aliasing of stills. While nothing the picture depends on changes (a paused
// window, capture --accumulate, a scene that does not move), the renderer moves the camera by a
// sub-pixel offset each frame (sss/pixel_jitter.h: the centre first, then Halton points) and this
// module keeps the weighted mean of the frames in the camera target: edges converge to the pixel's
// box-filtered coverage, and the translucent estimate to the mean of its frames, each weighted by
// the samples it holds (TranslucencyMethod::stillWeight). A change restarts the mean at the new
// frame, which is drawn at the pixel centres: playback looks as it did without render.aa.
#include <cstddef>

#include "gpu/gl_objects.h"
#include "gpu/program.h"
#include "gpu/shader_library.h"

namespace tallow::sss {

class StillAverage {
 public:
  explicit StillAverage(const gpu::ShaderLibrary& shaders);
  /// Folds `radiance` (the frame just drawn) into the mean with `weight` > 0 and writes the mean
  /// back into it; `first`: the still starts here (the mean is this frame).
  void add(const gpu::Texture& radiance, double weight, bool first);
  /// Frames in the current mean (0 before the first).
  int frames() const { return frames_; }
  std::size_t bytes() const { return history_.bytes(); }

 private:
  gpu::Program program_;
  gpu::Texture history_;
  double weightSum_ = 0.0;
  int frames_ = 0;
};

}  // namespace tallow::sss
