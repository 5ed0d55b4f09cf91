#pragma once
// SSLPV's medium grid (the paper's §3.2.1–3.2.2: σ_t, σ'_s and g per cell, "a separate grid" each):
// which LPV cells lie inside the translucent objects and with what material.
//   1. Solid voxelisation by parity (Eisemann and Décoret 2008, with the three-axis vote of
//      Nooruddin and Turk 2003 against meshes with holes): the objects are drawn orthographically
//      along x, y and z into columns of 2N × 2N sub-samples; every fragment flips, with atomic XOR,
//      the bits of the sub-samples behind it, so a bit ends set where a column crossed the surface
//      an odd number of times. One bit set of words per translucent object and axis.
//   2. A compute pass per cell: each of its 2 × 2 × 2 sub-samples is inside an object when at
//      least two of the three axes say so; the cell's σ_a, σ_s, g are the mean over its inside
//      sub-samples of the object's material, or of the mix with the object's second material where
//      it has a "volume" (shaders/peers/sslpv/volume.glsl); from them the grid's σ_t and σ'_s (shared
//      sslpvGridExtinction, sslpvScatteringFraction). A cell with no inside sub-sample is vacuum.
#include <glm/glm.hpp>

#include <vector>

#include "gpu/gl_objects.h"
#include "gpu/program.h"
#include "gpu/shader_library.h"
#include "sss/peers/sslpv_math.h"
#include "sss/scene.h"
#include "sss/scene_geometry.h"

namespace tallow::sss {

class SslpvMedium {
 public:
  explicit SslpvMedium(const gpu::ShaderLibrary& shaders);

  /// Voxelises the translucent objects (slots[objectIndex] ≥ 0, at most kMaxTranslucentObjects)
  /// into `grid` and fills the three medium textures.
  void build(const Scene& scene, const SceneGeometry& geometry, const std::vector<int>& slots, const SslpvGrid& grid);
  /// Every cell inside the medium with the same grid σ_t, σ'_s and g per band (tests).
  void fillUniform(int size, const glm::vec3& sigmaT, const glm::vec3& sigmaPrime, const glm::vec3& g);

  /// RGBA32F 3D, size³: rgb the grid's σ_t [mm⁻¹] per band, a 1 inside the medium, 0 in vacuum.
  const gpu::Texture& extinction() const { return extinction_; }
  /// rgb σ'_s per band, a the share of the cell's sub-samples inside an object.
  const gpu::Texture& scattering() const { return scattering_; }
  /// rgb g per band.
  const gpu::Texture& anisotropy() const { return anisotropy_; }
  int size() const { return extinction_.width(); }
  std::size_t bytes() const;

  /// Words of 32 bits per parity column for a grid of `size` cells (2 sub-samples per cell).
  static int parityWords(int size) { return (2 * size + 31) / 32; }

 private:
  void ensureTextures(int size);

  gpu::Program voxelize_, medium_;
  gpu::Texture parity_;  ///< r32ui 2D array: 2N × 2N × (slots · 3 axes · words)
  gpu::Texture extinction_, scattering_, anisotropy_;
  gpu::Buffer axisViews_;  ///< the three orthographic views (the layered passes' storage block)
};

}  // namespace tallow::sss
