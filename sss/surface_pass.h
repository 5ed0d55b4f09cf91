#pragma once
// The camera pass's GPU side (shaders/surface.*): every shape drawn into the camera target;
// opaque ones Lambertian, lit by the scene's lights with shadows, a uniform ambient sky and (with
// the radiosity maps) the VPLs' emergent light; translucent ones shaded as the frame's method says
// (sss/translucency_method.h). The pass that runs it every frame is CameraPass (sss/frame_passes.h).
#include <map>
#include <string>

#include "gpu/gl_objects.h"
#include "gpu/program.h"
#include "sss/pass.h"
#include "sss/scene.h"

namespace tallow::sss {

/// Upper bounds of the shader's light arrays (shaders/common/lights.glsl).
constexpr int kMaxDirectionalLights = 32;
constexpr int kMaxPointLights = 8;

class SurfacePass {
 public:
  explicit SurfacePass(const gpu::ShaderLibrary& shaders);
  /// The scene's environment map (lat-long radiance, sss::Environment conventions) for the
  /// specular reflection on translucent objects; reads the file (throws std::runtime_error).
  void setEnvironment(const Environment& environment);
  /// Draws the frame into context.target (already sized and cleared by the caller), with the shadow
  /// maps of the ShadowPass module and the frame's method's variant of the shader (its
  /// surfaceShader() as TALLOW_SURFACE_METHOD), which it binds.
  void render(const FrameContext& context);

 private:
  /// sss.maps=auto: the camera's coverage histograms from the frame's coverage bins, one count per
  /// visible pixel (shaders/maps/coverage_histogram.comp), into the buffer MapCoverageProbe bound.
  void countCoverage(const FrameContext& context);

  /// The variant of the camera pass for `method`, compiled on its first frame and kept.
  gpu::Program& variant(const TranslucencyMethod& method);

  const gpu::ShaderLibrary& shaders_;
  std::map<std::string, gpu::Program> variants_;  ///< by the method's surfaceShader()
  gpu::Program coverageHistogram_;
  gpu::Texture environment_;
  float environmentRotationDeg_ = 0.0f, environmentScale_ = 1.0f;
};

}  // namespace tallow::sss
