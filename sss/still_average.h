#pragma once
// render.aa: anti-aliasing of stills. While nothing the picture depends on changes (a paused
// window, capture --accumulate, a scene that does not move), the renderer moves the camera by a
// sub-pixel offset each frame (sss/pixel_jitter.h: the centre first, then Halton points) and this
// module keeps the frames' mean in the camera target: edges converge to the pixel's box-filtered
// coverage. The translucent part of the radiance (CameraTarget::translucent) is kept apart: where
// a translucent surface is drawn its estimate is averaged with each frame weighted by the samples
// it holds (TranslucencyMethod::stillWeight), and that mean is scaled by the share of frames that
// drew it; everything else (opaque surfaces, specular reflection, the flame, the background) is
// the frames' plain mean. Weighting whole frames instead let an edge pixel's coverage follow the
// weights, so the late sub-pixel positions counted more than the early ones: at the candle's
// grazing drip silhouettes one pixel came out 4× its neighbours (issue 36).
// A change restarts the mean at the new frame, which is drawn at the pixel centres: playback
// looks as it did without render.aa.
#include <cstddef>

#include "gpu/gl_objects.h"
#include "gpu/program.h"
#include "gpu/shader_library.h"

namespace tallow::sss {

class StillAverage {
 public:
  explicit StillAverage(const gpu::ShaderLibrary& shaders);
  /// Folds the frame just drawn into the means and writes the still's picture back into
  /// `radiance`: `radiance` the frame's RGBA, `translucent` its translucent part (rgb, a: 1 where a
  /// translucent surface is drawn, 0 elsewhere), `weight` > 0 the translucent estimate's weight;
  /// `first`: the still starts here (the picture is this frame).
  void add(const gpu::Texture& radiance, const gpu::Texture& translucent, double weight, bool first);
  /// Frames in the current mean (0 before the first).
  int frames() const { return frames_; }
  std::size_t bytes() const { return rest_.bytes() + translucentSum_.bytes() + translucentShare_.bytes(); }
  /// What bytes() is once a width × height frame was added (the memory budget's figure).
  static std::size_t bytesFor(int width, int height);

 private:
  gpu::Program program_;
  gpu::Texture rest_;              ///< RGBA32F: the frames' mean of radiance − translucent
  gpu::Texture translucentSum_;    ///< RGBA32F: Σ w·h·T (rgb) and Σ w·h (a) over the frames
  gpu::Texture translucentShare_;  ///< R32F: the frames' mean of h
  int frames_ = 0;
};

}  // namespace tallow::sss
