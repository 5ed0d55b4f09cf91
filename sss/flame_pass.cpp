#include "sss/flame_pass.h"

#include <cmath>

#include "sss/field_source.h"
#include "sss/light_uniforms.h"
#include "sss/scene_geometry.h"

namespace tallow::sss {

namespace {

/// Rows of the flame's sheet (a triangle strip of 2 × rows vertices): the sway bends it.
constexpr int kFlameRows = 12;

/// The candle a light follows, when it is a flame to draw.
const SceneObject* followedCandle(const Scene& scene, const Light& light) {
  if (light.kind != LightKind::Point || light.follow < 0) return nullptr;
  const SceneObject& o = scene.objects.at(static_cast<std::size_t>(light.follow));
  return o.shape == ShapeKind::Field && fieldCarriesFlame(o.field) ? &o : nullptr;
}

}  // namespace

std::vector<FlameSheet> flameSheets(const Scene& scene, double timeS, const RenderSettings& settings) {
  std::vector<FlameSheet> out;
  if (!settings.flame) return out;
  for (std::size_t i = 0; i < scene.lights.size(); ++i) {
    const Light& light = scene.lights[i];
    if (!followedCandle(scene, light)) continue;
    const FollowedFlame f = followedFlame(scene, light, timeS);
    const glm::vec3 axis(f.model * glm::vec4(0.0f, 1.0f, 0.0f, 0.0f));
    FlameSheet s;
    s.base = glm::vec3(f.model * glm::vec4(glm::vec3(f.flame.base), 1.0f));
    s.up = axis / f.scale;
    s.height = static_cast<float>(f.flame.height) * f.scale;
    s.halfWidth = static_cast<float>(f.flame.halfWidth) * f.scale;
    s.sway = glm::vec3(f.model * glm::vec4(glm::vec3(f.flame.sway), 0.0f));
    s.radianceScale = static_cast<float>(f.radianceScale(light) * std::exp2(settings.flameExposureEv));
    s.light = static_cast<int>(i);
    out.push_back(s);
  }
  return out;
}

glm::dvec3 flameSeenAlong(const glm::dvec3& origin, const glm::dvec3& dir, const FlameSheet& s) {
  return geometry::flameSeenAlong(origin, dir, glm::dvec3(s.base), glm::dvec3(s.up), double(s.height),
                                  double(s.halfWidth), glm::dvec3(s.sway));
}

void setFlameMirrorUniforms(gpu::Program& p, const Scene& scene, const std::vector<FlameSheet>& flames) {
  constexpr std::size_t kMaxFlames = 8;  // surface.frag MAX_FLAMES
  std::vector<glm::vec3> base, up, sway, size;
  std::vector<int> pointLight;
  for (std::size_t i = 0; i < flames.size() && i < kMaxFlames; ++i) {
    base.push_back(flames[i].base);
    up.push_back(flames[i].up);
    sway.push_back(flames[i].sway);
    size.emplace_back(flames[i].height, flames[i].halfWidth, flames[i].radianceScale);
    pointLight.push_back(flames[i].light >= 0 ? pointLightUniformIndex(scene, static_cast<std::size_t>(flames[i].light))
                                              : -1);
  }
  const int count = static_cast<int>(base.size());
  p.set("uFlameCount", count);
  if (count == 0) return;
  p.set("uFlameBase", base.data(), count);
  p.set("uFlameUp", up.data(), count);
  p.set("uFlameSway", sway.data(), count);
  p.set("uFlameSize", size.data(), count);
  glProgramUniform1iv(p.id(), p.location("uFlamePointLight"), count, pointLight.data());
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
  return {{resource::kCamera, "render.flame", "flame.exposure_ev", "scene.light_placement", "scene.light_intensity",
           "scene.camera"},
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
  // The translucent part (attachment 3) stays the wax's: flame.frag does not write it.
  glColorMaski(3, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  p.use();
  emptyVao_->bind();
  // The lights as sceneAtTime placed them: each the emission of the flame drawn here.
  for (const FlameSheet& s : flameSheets(context.scene(), context.state.timeS, context.settings())) {
    p.set("uBase", s.base);
    p.set("uUp", s.up);
    p.set("uHeight", s.height);
    p.set("uHalfWidth", s.halfWidth);
    p.set("uSway", s.sway);
    p.set("uRadianceScale", s.radianceScale);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 2 * kFlameRows);
  }
  glBindVertexArray(0);
  glUseProgram(0);
  glBlendFunc(GL_ONE, GL_ZERO);  // GL's default, for every draw buffer
  glColorMaski(3, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDisable(GL_BLEND);
  glDepthMask(GL_TRUE);
  glDisable(GL_DEPTH_TEST);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

}  // namespace tallow::sss
