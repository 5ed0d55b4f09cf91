#include "sss/flame_pass.h"

#include <cmath>

#include "sss/field_source.h"
#include "sss/light_uniforms.h"
#include "sss/scene_geometry.h"

namespace tallow::sss {

namespace {

/// The candle a light follows, when it is a flame to draw.
const SceneObject* followedCandle(const Scene& scene, const Light& light) {
  if (light.kind != LightKind::Point || light.follow < 0) return nullptr;
  const SceneObject& o = scene.objects.at(static_cast<std::size_t>(light.follow));
  return o.shape == ShapeKind::Field && o.field.kind == FieldKind::Candle ? &o : nullptr;
}

}  // namespace

double FlameShape::effectiveArea() const {
  // ∫₀¹ 2 w(v) (1.3 − 0.6 v) dv with w = √v (1 − v) / f(1/3): 1.3 B(3/2, 2) − 0.6 B(5/2, 2), where
  // B(a, 2) = 1/a − 1/(a + 1), times 2 / f(1/3), f(1/3) = √(1/3) · 2/3 (flame.frag's profile).
  const double widest = std::sqrt(1.0 / 3.0) * 2.0 / 3.0;
  const double profile = 2.0 / widest * (1.3 * (1.0 / 1.5 - 1.0 / 2.5) - 0.6 * (1.0 / 2.5 - 1.0 / 3.5));
  return halfWidth * height * profile;
}

int flameCount(const FrameState& state) {
  if (!state.settings.flame) return 0;
  int n = 0;
  for (const Light& l : state.scene.lights) n += followedCandle(state.scene, l) ? 1 : 0;
  return n;
}

std::string FlamePass::reason(const FrameState& state) const {
  return std::to_string(flameCount(state)) +
         " candle flame(s): an emissive teardrop on the wick, added to the camera target after the surface "
         "(radiance = the light's intensity over its area), not in the light G-buffers or maps";
}

PassIo FlamePass::io(const FrameState&) const {
  // Drawn over each new picture of the camera pass (hence kCamera: it reruns whenever that does).
  return {{resource::kCamera, "render.flame", "scene.light_placement", "scene.light_intensity", "scene.camera"},
          {},
          {}};
}

void FlamePass::run(FrameContext& context, bool /*changed*/) {
  if (!program_)
    program_ = std::make_unique<gpu::Program>(
        context.shaders, gpu::ProgramDesc{{{GL_VERTEX_SHADER, "flame.vert"}, {GL_FRAGMENT_SHADER, "flame.frag"}}});
  if (!emptyVao_) emptyVao_ = std::make_unique<gpu::VertexArray>();
  gpu::Program& p = *program_;
  setCameraUniforms(p, context.camera());
  const Scene& scene = context.scene();
  const FlameShape shape;
  const CameraTarget& t = context.target;
  t.framebuffer.bind();
  glViewport(0, 0, context.settings().width, context.settings().height);
  // Behind the wax it is hidden; where it shows it adds its light to what is behind it.
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_FALSE);
  glDisable(GL_CULL_FACE);
  glEnable(GL_BLEND);
  glBlendFunci(0, GL_ONE, GL_ONE);         // radiance: added
  glBlendFunci(1, GL_ZERO, GL_SRC_COLOR);  // coverage: alpha halved where the flame is in front
  p.use();
  emptyVao_->bind();
  for (const Light& light : scene.lights) {
    const SceneObject* candle = followedCandle(scene, light);
    if (!candle) continue;
    const geometry::CandleParams params = candleParams(candle->field);
    const glm::mat4 model = SceneGeometry::modelMatrix(*candle, geometry::Aabb{});
    const glm::vec3 axis(model * glm::vec4(0.0f, 1.0f, 0.0f, 0.0f));
    const float scale = glm::length(axis);  // world units per field unit
    const glm::vec3 up = axis / scale;
    // The base 1 mm below the wick's tip, which is flameLift below the light.
    const float below = static_cast<float>(params.flameLift + 0.001) * scale;
    p.set("uBase", light.position - below * up);
    p.set("uUp", up);
    p.set("uHeight", static_cast<float>(shape.height) * scale);
    p.set("uHalfWidth", static_cast<float>(shape.halfWidth) * scale);
    p.set("uRadiance", light.intensity / static_cast<float>(shape.effectiveArea() * scale * scale));
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
  }
  glBindVertexArray(0);
  glUseProgram(0);
  glBlendFunc(GL_ONE, GL_ZERO);  // GL's default, for every draw buffer
  glDisable(GL_BLEND);
  glDepthMask(GL_TRUE);
  glDisable(GL_DEPTH_TEST);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

}  // namespace tallow::sss
