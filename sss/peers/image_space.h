#pragma once
// Local subsurface scattering in image space (Mertens, Kautz, Bekaert, Van Reeth and Seidel 2003,
// "Efficient rendering of local subsurface scattering", "the image-space paper"), method
// `image-space` (docs/image-space.md). Three passes before the surface pass:
//   1. image_space.gbuffer: the camera's view of every object: world position with the translucent
//      slot, normal, and the irradiance transmitted into the medium E·F_t from every light with its
//      shadow map (shaders/peers/image_space/gbuffer.frag); once per accumulation (it depends on nothing
//      that changes between its frames);
//   2. image_space.scatter: the frame's sample pattern (pattern.comp: exact importance samples of
//      the standard dipole's R_d per colour band and uniform samples on a disc, with balance-
//      heuristic weights, one set per place of a T×T interleaving tile), then per translucent pixel
//      B(x_o) = Σ_j R_d(r_j) E(p_j) (dA_p/dA_p')_j w_j from the samples of x_o's tangent plane
//      projected into the image (scatter.frag);
//   3. image_space.combine: the geometry-aware mean over each pixel's T×T window (the T² sets),
//      added to the accumulation of the frames while nothing changes (combine.frag).
// The surface pass reads B at the pixel (shaders/peers/image_space/result.glsl) and shades
// L = F_t(ω_o)/π · B + the Fresnel-weighted specular of the other methods.
#include <cstddef>
#include <string>
#include <vector>

#include "gpu/gl_objects.h"
#include "gpu/program.h"
#include "gpu/shader_library.h"
#include "sss/peers/camera_gbuffer.h"
#include "sss/render_settings.h"
#include "sss/scene.h"
#include "sss/scene_geometry.h"
#include "sss/shadow_pass.h"
#include "sss/view_setup.h"

namespace tallow::sss {

/// One entry of the sample pattern as the GPU stores it (std430; shaders/peers/image_space/pattern.glsl).
struct ImageSpacePatternRecord {
  float offsetX, offsetY;  ///< [mm] along x_o's tangent frame
  float weight;            ///< balance-heuristic weight over the density [mm²]
  float unused0;
  float coverage[3];       ///< per band
  float unused1;
};

class ImageSpaceSss {
 public:
  explicit ImageSpaceSss(const gpu::ShaderLibrary& shaders);

  /// True when the scene has translucent objects and `settings` selects method image-space.
  static bool applies(const Scene& scene, const RenderSettings& settings);
  /// Throws std::invalid_argument (one line) when the scene has more translucent objects than the
  /// passes hold or the sample pattern exceeds this GPU's shader-storage block size.
  static void checkLimits(const Scene& scene, const RenderSettings& settings);
  /// Why each of the three passes runs, for the frame plan (`pass`: "image_space.gbuffer", …).
  static std::string describe(const Scene& scene, const RenderSettings& settings, const std::string& pass);
  /// Pass 1: the camera's G-buffer with the irradiance (deterministic).
  void renderGBuffer(const Scene& scene, const RenderSettings& settings, const SceneGeometry& geometry,
                     const CameraView& camera, const ShadowPass& shadows);
  /// Empties the accumulation (the next frame is its first).
  void restart();
  /// Pass 2 (the pattern of accumulated frame frames(), then the per-pixel estimate).
  void scatter(const Scene& scene, const RenderSettings& settings, const CameraView& camera);
  /// Pass 3; counts the frame.
  void combine(const RenderSettings& settings);

  /// result.glsl's uniforms on a program that includes it; the accumulation (if `self` is not
  /// null) on texture units firstUnit and firstUnit + 1, which are set either way.
  static void setSurfaceUniforms(gpu::Program& program, const ImageSpaceSss* self, const RenderSettings& settings,
                                 GLuint firstUnit);

  int frames() const { return frames_; }  ///< F, frames accumulated
  std::size_t bytes() const;
  /// For tests: the G-buffer, the last scatter estimate, the accumulation and the pattern.
  const gpu::Texture& positions() const { return gbuffer_.positions(); }
  const gpu::Texture& irradiance() const { return gbuffer_.irradiance(); }
  const gpu::Texture& scatterSum() const { return sum_; }
  const gpu::Texture& accumulatedSum() const { return accumSum_; }
  const gpu::Texture& accumulatedCoverage() const { return accumCoverage_; }
  const gpu::Buffer& pattern() const { return pattern_; }
  /// Translucent slot of each scene object (−1 for opaque), valid after renderGBuffer.
  const std::vector<int>& slots() const { return gbuffer_.slots(); }

 private:
  void ensureTargets(int width, int height);

  CameraIrradianceGBuffer gbuffer_;  ///< pass 1
  gpu::Program patternProgram_, scatterProgram_, combineProgram_;
  gpu::Texture sum_, coverage_;                           ///< pass 2
  gpu::Texture accumSum_, accumCoverage_;                 ///< pass 3, read by the surface pass
  gpu::Framebuffer scatterTarget_, accumTarget_;
  gpu::Buffer pattern_;
  gpu::VertexArray emptyVao_;
  int frames_ = 0;
};

}  // namespace tallow::sss
