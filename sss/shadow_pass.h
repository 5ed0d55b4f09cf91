#pragma once
// Shadow maps of the lights that cast shadows: one layer of a 2D depth array per directional
// light (orthographic, fitted to the scene), one cube of a cube-map array per point light (each
// face's perspective depth, which the receivers compute: common/cube_shadow_depth.glsl). Receivers
// sample them with hardware comparison. The maps outlive a
// frame: the passes shadow.directional and shadow.point (sss/frame_passes.h) redraw them only when
// the geometry, the lights or the map size changed; receivers use a light's layer only while
// render.shadows is on and the light casts shadows (setLightUniforms).
#include <glm/glm.hpp>

#include <vector>

#include "gpu/gl_objects.h"
#include "gpu/program.h"
#include "sss/render_settings.h"
#include "sss/scene.h"
#include "sss/scene_geometry.h"

namespace tallow::sss {

struct ShadowLayers {
  std::vector<int> directionalLayer;  ///< per scene light: layer, or −1
  std::vector<int> pointCube;         ///< per scene light: cube, or −1
  std::vector<glm::mat4> directionalMatrix;  ///< per scene light: world → [0,1]³
  std::vector<float> directionalTexel;       ///< per scene light: world size of one texel
  std::vector<float> pointRange;             ///< per scene light
  float pointTexelAngle = 0.0f;
};

class ShadowPass {
 public:
  explicit ShadowPass(const gpu::ShaderLibrary& shaders);

  static bool needsDirectional(const Scene& scene, const RenderSettings& settings);
  static bool needsPoint(const Scene& scene, const RenderSettings& settings);

  /// Marks every light of a scene with `lightCount` lights unshadowed.
  void reset(std::size_t lightCount);
  /// Renders the directional-light shadow maps (if any light needs one); the layers of the other
  /// lights say unshadowed. The point lights' layers are left as they are.
  void renderDirectional(const Scene& scene, const RenderSettings& settings, const SceneGeometry& geometry);
  /// Renders the point-light cube shadow maps (if any light needs one); likewise for point lights.
  void renderPoint(const Scene& scene, const RenderSettings& settings, const SceneGeometry& geometry);

  const ShadowLayers& layers() const { return layers_; }
  /// Bind to the units the receiver shader expects; unused maps get a 1-texel dummy (lit).
  void bind(GLuint directionalUnit, GLuint pointUnit) const;
  void bindPoint(GLuint pointUnit) const;
  std::size_t bytes() const { return directional_.bytes() + point_.bytes(); }

 private:
  /// Makes `texture` a depth map of `size` and `layers` (cube: 6 faces each) unless it is one
  /// already, and keeps one target per layer (face) in `targets`, released when it was remade.
  void ensure(gpu::Texture& texture, std::vector<gpu::TargetFramebuffer>& targets, bool cube, int size, int layers);
  void resetDirectional(std::size_t lightCount);
  void resetPoint(std::size_t lightCount);
  gpu::Program program_;
  gpu::Texture directional_, point_;
  std::vector<gpu::TargetFramebuffer> directionalTargets_, pointTargets_;  ///< per layer / per cube face
  gpu::Texture dummyDirectional_, dummyPoint_;
  ShadowLayers layers_;
};

}  // namespace tallow::sss
