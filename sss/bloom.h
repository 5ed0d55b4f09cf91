#pragma once
// render.bloom: glare around light brighter than the display's white (a candle's flame), applied to
// the HDR picture before tone mapping by an energy-conserving point-spread function
// (shaders/camera/bloom.comp: the light above white at the picture's exposure, spread by a mean of
// box-filtered mip levels, equal energy per octave of radius, as the eye's glare PSF falls off as
// 1/r²; a share of it moved, none added). It changes what is shown — the window, PNGs, videos —
// and not the radiance the EXR holds and the errors are measured on: it models the eye and the
// camera lens, not the scene (docs/commands.md).
#include <cstddef>

#include "gpu/gl_objects.h"
#include "gpu/program.h"
#include "gpu/shader_library.h"

namespace tallow::sss {

class Bloom {
 public:
  /// Octaves of radius the glare spans: up to 2^kLevels pixels, 64 (a sixth of a 360-pixel picture).
  static constexpr int kLevels = 6;

  explicit Bloom(const gpu::ShaderLibrary& shaders);
  /// GPU memory apply() allocates for a width × height picture (the mip chain and the output).
  static std::size_t bytesFor(int width, int height);
  /// The picture `radiance` with a share `share` ∈ (0, 1] of its light above white (at the exposure
  /// scale `exposureScale`) spread by the PSF, into output() (allocated on the first call and at a
  /// new size). With `coverage` (the camera's), the output's alpha is its code
  /// (common/coverage_masks.glsl); without, the picture's alpha.
  void apply(const gpu::Texture& radiance, float share, float exposureScale, const gpu::Texture* coverage = nullptr);
  const gpu::Texture& output() const { return output_; }
  std::size_t bytes() const { return pyramid_.bytes() + output_.bytes(); }

 private:
  gpu::Program program_;
  gpu::Texture pyramid_, output_;
};

}  // namespace tallow::sss
