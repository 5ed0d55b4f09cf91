#pragma once
// render.local_exposure: local adaptation of the picture shown, as the eye adapts to the dim table
// beside a bright candle (shaders/camera/local_exposure.comp). The log luminance's edge-aware base
// layer (Durand and Dorsey 2002), computed on a bilateral grid (Chen, Paris and Durand 2007), is
// lifted toward mid grey by a share s of its distance below it: a region s·d stops under mid grey
// before is (1 − s)·d under it after; above mid grey nothing changes, so highlights do not clip
// more, and within a region the detail (the picture's ratios to its base) is kept; a pixel blended
// from both sides of an edge is shown as the blend of what the two sides show. Like the glare
// it changes what is shown — the window, PNGs, videos — not the radiance in the EXR
// (docs/presets.md, Local exposure).
#include <cstddef>

#include "gpu/gl_objects.h"
#include "gpu/program.h"
#include "gpu/shader_library.h"

namespace tallow::sss {

class LocalExposure {
 public:
  /// Range bins of the grid (local_exposure.comp's kBins).
  static constexpr int kBins = 22;

  explicit LocalExposure(const gpu::ShaderLibrary& shaders);
  /// Pixels per grid cell along x and y for a width × height picture: σ_s, 2% of its larger side
  /// (Durand and Dorsey 2002, §5.2), at least 2.
  static int cellFor(int width, int height);
  /// GPU memory apply() allocates for a width × height picture (two grids, the gains and the output).
  static std::size_t bytesFor(int width, int height);
  /// The picture `picture` (linear) with its base layer's shadows lifted by the share `strength` ∈
  /// (0, 1] toward mid grey at the exposure scale `exposureScale`, into output() (allocated on the
  /// first call and at a new size). With `coverage` (the camera's), the output's alpha is its code
  /// (common/coverage_masks.glsl); without, the picture's alpha.
  void apply(const gpu::Texture& picture, float strength, float exposureScale, const gpu::Texture* coverage = nullptr);
  const gpu::Texture& output() const { return output_; }
  std::size_t bytes() const { return grid_[0].bytes() + grid_[1].bytes() + output_.bytes() + gain_.bytes(); }

 private:
  gpu::Program program_;
  gpu::Texture grid_[2], output_, gain_;
};

}  // namespace tallow::sss
