#pragma once
// The visible flame of a burning candle (issues 16 and 35): for each point light that follows a
// candle field, the flame of geometry/candle_flame.h — a soft-edged teardrop on the wick, its radiance
// shaders/flame/flame_profile.glsl (a blackbody profile, a dark cone, a blue base), bent by its sway
// and flickering with it — on a camera-facing sheet drawn into the camera target after the surface
// pass (depth-tested against it, added to what is behind: a flame is transparent) and nowhere else:
// not in the shadow maps, the light G-buffers or the radiosity maps, whose light is the point light's.
// The point light is the same emission (sceneAtTime): the flame's flux is the light's intensity, its
// emission centre the light's position.
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gpu/gl_objects.h"
#include "gpu/program.h"
#include "sss/frame_passes.h"

namespace tallow::sss {

/// Lights drawn as flames: point lights that follow a candle field, when render.flame is on.
int flameCount(const FrameState& state);

/// One drawn flame in world units (shaders/flame.vert's uniforms, shaders/flame/flame_mirror.glsl's
/// arguments): its base on the axis, the axis, where the sway moves the tip, its height and widest
/// half-width, and the radiance per unit of flameProfile as drawn (flame.exposure_ev included).
struct FlameSheet {
  glm::vec3 base{0.0f}, up{0.0f, 1.0f, 0.0f}, sway{0.0f};
  float height = 0.0f, halfWidth = 0.0f, radianceScale = 0.0f;
  /// The point light the flame is (its index in Scene::lights): a mirror sees the flame only where
  /// that light reaches, so that the puddle at the foot does not reflect it through the wax.
  int light = -1;
};

/// The flames of `scene` (as sceneAtTime placed its lights) at t, as drawn; empty when render.flame
/// is off.
std::vector<FlameSheet> flameSheets(const Scene& scene, double timeS, const RenderSettings& settings);

/// What `sheet` shows to a viewer at `origin` looking along unit `dir`, per unit of radianceScale
/// (shaders/flame/flame_mirror.glsl in double: the reflection surface.frag adds on a mirror-like
/// translucent surface, the pool's above all).
glm::dvec3 flameSeenAlong(const glm::dvec3& origin, const glm::dvec3& dir, const FlameSheet& sheet);

/// surface.frag's flame uniforms (uFlameCount, the sheets and their point lights' indices, at most
/// its MAX_FLAMES = 8).
void setFlameMirrorUniforms(gpu::Program& program, const Scene& scene, const std::vector<FlameSheet>& flames);

class FlamePass final : public FramePass {
 public:
  std::string name() const override { return "flame"; }
  bool needed(const FrameState& state) const override { return flameCount(state) > 0; }
  std::string reason(const FrameState& state) const override;
  PassIo io(const FrameState& state) const override;
  void run(FrameContext& context, bool changed) override;

 private:
  std::unique_ptr<gpu::Program> program_;  ///< made on the first run (needs the GL context)
  std::unique_ptr<gpu::VertexArray> emptyVao_;  ///< the quad's corners come from gl_VertexID
};

}  // namespace tallow::sss
