#pragma once
// The engines' screen-space subsurface scattering as a peer (`method=burley`, docs/burley.md):
// Christensen and Burley's normalised diffusion profile (shaders/peers/burley/profile.glsl; the
// parameters A and d of each colour band from the material's σ_a, σ_s, g, η) applied in screen
// space to the irradiance of the translucent pixels, as Unreal's Burley SSS does (Xie et al. 2020:
// importance-sampled discs facing the camera, the profile's world-space radius projected per pixel,
// samples on other objects skipped and the weights renormalised, so that edges are not darkened),
// plus transmission through thin parts from the shadow maps (the thickness between a point and the
// first surface its light sees, through the profile's transmittance: Unity HDRP's "thick object"
// mode, Jimenez et al. 2010). Two passes before the camera pass:
//   1. burley.gbuffer: the camera's irradiance G-buffer (sss/peers/camera_gbuffer.h), deterministic;
//   2. burley.scatter: per translucent pixel, N profile samples (a new rotation each frame, averaged
//      by a still's frames like engines' temporal filters) and the transmitted light
//      (shaders/peers/burley/scatter.comp) into the radiosity B the camera pass reads at the pixel:
//      L = F_t(ω_o)/π · B, as the image-space peer.
#include <cstddef>
#include <string>
#include <vector>

#include "gpu/gl_objects.h"
#include "gpu/program.h"
#include "gpu/shader_library.h"
#include "sss/pass.h"
#include "sss/peers/camera_gbuffer.h"
#include "sss/translucency_method.h"

namespace tallow::sss {

namespace resource {
inline constexpr const char* kBurleyGBuffer = "burley.gbuffer";
inline constexpr const char* kBurleyRadiosity = "burley.radiosity";
}  // namespace resource

class BurleySss {
 public:
  explicit BurleySss(const gpu::ShaderLibrary& shaders);

  /// True when the scene has translucent objects and `settings` selects method burley.
  static bool applies(const Scene& scene, const RenderSettings& settings);
  /// Throws std::invalid_argument (one line) when the scene has more translucent objects than the
  /// passes hold.
  static void checkLimits(const Scene& scene, const RenderSettings& settings);
  /// Why each pass runs, for the frame plan ("burley.gbuffer", "burley.scatter").
  static std::string describe(const Scene& scene, const RenderSettings& settings, const std::string& pass);
  /// What the passes allocate at width × height with `kernel` (separable: one more target and the taps).
  static std::size_t bytesFor(int width, int height, BurleyKernel kernel);

  void renderGBuffer(const Scene& scene, const RenderSettings& settings, const SceneGeometry& geometry,
                     const CameraView& camera, const ShadowPass& shadows);
  /// The frame's samples (rotated by `frame`) and the transmitted light, into radiosity().
  void scatter(const Scene& scene, const RenderSettings& settings, const CameraView& camera, const ShadowPass& shadows,
               int frame);

  /// The camera pass's sampler (uBurleyRadiosity) on `unit`, set either way; the radiosity bound
  /// when `self` is not null.
  static void setSurfaceUniforms(gpu::Program& program, const BurleySss* self, GLuint unit);

  const CameraIrradianceGBuffer& gbuffer() const { return gbuffer_; }
  const gpu::Texture& radiosity() const { return radiosity_; }  ///< RGBA32F: B [W/m²], alpha 1 where translucent
  std::size_t bytes() const {
    return gbuffer_.bytes() + radiosity_.bytes() + intermediate_.bytes() + taps_.size();
  }

 private:
  void ensureTarget(gpu::Texture& texture, int width, int height);
  /// The separable kernel's taps of every slot, uploaded when the materials or the count change.
  void updateTaps(const Scene& scene, const RenderSettings& settings);

  CameraIrradianceGBuffer gbuffer_;
  gpu::Program scatterProgram_, separableProgram_;
  gpu::Texture radiosity_;
  gpu::Texture intermediate_;  ///< the separable kernel's first pass
  gpu::Buffer taps_;           ///< BurleyTapGpu per slot and tap (separable.comp)
  std::vector<float> tapsKey_;  ///< the materials and tap count taps_ holds
  gpu::Sampler depthValues_;  ///< the shadow maps read as depths (their own compare mode off)
};

/// burley.gbuffer (deterministic: runs when what it draws changes).
class BurleyGBufferPass final : public Pass {
 public:
  std::string name() const override { return "burley.gbuffer"; }
  std::string reason(const FrameState& state) const override;
  PassIo io(const FrameState& state) const override;
  void run(FrameContext& context, bool changed) override;
};

/// burley.scatter: a new rotation of the samples on each of a still's render.aa frames (its average
/// is what engines' temporal filters make of the rotations); then it keeps its output.
class BurleyScatterPass final : public Pass {
 public:
  std::string name() const override { return "burley.scatter"; }
  std::string reason(const FrameState& state) const override;
  PassIo io(const FrameState& state) const override;
  /// The disc kernel draws a new rotation for each of a still's frames; the separable one is the same
  /// every frame.
  bool runsAgain(const FrameState& state) const override {
    return frames_ < (state.settings.burley.kernel == BurleyKernel::Disc ? state.settings.aaSamples : 1);
  }
  bool refines() const override { return true; }
  void run(FrameContext& context, bool changed) override;

 private:
  int frames_ = 0;  ///< runs since the last restart (the rotation of the next is this)
};

class BurleyMethod final : public TranslucencyMethod {
 public:
  SssMethod id() const override { return SssMethod::Burley; }
  void checkLimits(const FrameState& state) const override;
  std::vector<Pass*> passes(const FrameState& state) override;
  bool shadesTranslucent(const FrameState& state) const override;
  std::string surfaceShader() const override { return "peers/burley/surface.glsl"; }
  void addMemory(const Scene& scene, const RenderSettings& settings, const BudgetSizes& sizes,
                 FrameMemory& memory) const override;
  std::string describeShading(const FrameState& state) const override;
  PassIo surfaceIo(const FrameState& state) const override;
  int surfaceUnits() const override { return 1; }
  void bindSurface(gpu::Program& program, const FrameContext& context, GLuint firstUnit) const override;

 private:
  BurleyGBufferPass gbuffer_;
  BurleyScatterPass scatter_;
};

}  // namespace tallow::sss
