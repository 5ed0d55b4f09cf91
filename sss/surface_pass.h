#pragma once
// Lambertian shading of every shape, lit by the scene's lights with shadows and a uniform
// ambient sky, into a linear HDR target with depth.
#include "gpu/gl_objects.h"
#include "gpu/program.h"
#include "sss/radiosity_maps.h"
#include "sss/scene.h"
#include "sss/scene_geometry.h"
#include "sss/shadow_pass.h"
#include "sss/view_setup.h"

namespace tallow::sss {

/// Upper bounds of the shader's light arrays (shaders/common/lights.glsl).
constexpr int kMaxDirectionalLights = 32;
constexpr int kMaxPointLights = 8;

class SurfacePass {
 public:
  explicit SurfacePass(const gpu::ShaderLibrary& shaders);
  /// Draws into `target` (already sized and cleared by the caller). With `maps` (not null),
  /// translucent objects are shaded from the scattered radiosity maps (Algorithm 1, Eq. 5).
  void render(const Scene& scene, const RenderSettings& settings, const SceneGeometry& geometry,
              const CameraView& camera, const ShadowPass& shadows, const RadiosityMaps* maps,
              const gpu::Framebuffer& target, int width, int height);

 private:
  gpu::Program program_;
};

}  // namespace tallow::sss
