#include "sss/surface_pass.h"

#include "gpu/hdr_io.h"
#include "sss/flame_pass.h"
#include "sss/light_uniforms.h"
#include "sss/shadow_pass.h"
#include "sss/translucency_method.h"
#include "sss/translucent_slots.h"

namespace tallow::sss {
namespace {
constexpr GLuint kDirectionalShadowUnit = 0;
constexpr GLuint kPointShadowUnit = 1;
constexpr GLuint kEnvironmentUnit = 2;
constexpr GLuint kFirstMethodUnit = 3;  // then the frame's method's units (its variant of the pass)

}  // namespace

SurfacePass::SurfacePass(const gpu::ShaderLibrary& shaders)
    : shaders_(shaders), coverageHistogram_(shaders, {{{GL_COMPUTE_SHADER, "maps/coverage_histogram.comp"}}}) {}

gpu::Program& SurfacePass::variant(const TranslucencyMethod& method) {
  const std::string file = method.surfaceShader();
  auto it = variants_.find(file);
  if (it == variants_.end()) {
    gpu::ProgramDesc desc{{{GL_VERTEX_SHADER, "surface.vert"}, {GL_FRAGMENT_SHADER, "surface.frag"}},
                          {"TALLOW_SURFACE_METHOD \"" + file + "\""}};
    it = variants_.emplace(file, gpu::Program(shaders_, desc)).first;
  }
  return it->second;
}

void SurfacePass::setEnvironment(const Environment& environment) {
  const gpu::Image map = gpu::readHdr(environment.file);
  environment_ = gpu::Texture::create2D(GL_RGBA32F, map.width, map.height);
  glTextureSubImage2D(environment_.id(), 0, 0, 0, map.width, map.height, GL_RGBA, GL_FLOAT, map.pixels.data());
  environment_.setFilter(GL_LINEAR, GL_LINEAR);
  glTextureParameteri(environment_.id(), GL_TEXTURE_WRAP_S, GL_REPEAT);         // azimuth wraps
  glTextureParameteri(environment_.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);  // poles
  environmentRotationDeg_ = environment.rotationDeg;
  environmentScale_ = environment.scale;
}

void SurfacePass::render(const FrameContext& context) {
  const Scene& scene = context.scene();
  const RenderSettings& settings = context.settings();
  gpu::Program& p = variant(context.method);
  setLightUniforms(p, scene, settings, *context.modules.find<ShadowPass>(), kDirectionalShadowUnit, kPointShadowUnit);
  p.set("uAmbient", scene.ambient);
  setCameraUniforms(p, context.camera());
  p.set("uSpecular", settings.specular ? 1 : 0);
  p.set("uEnvironment", environment_.id() ? 1 : 0);
  p.set("uEnvMap", static_cast<int>(kEnvironmentUnit));
  p.set("uEnvRotation", glm::radians(environmentRotationDeg_));
  p.set("uEnvScale", environmentScale_);
  if (environment_.id()) environment_.bind(kEnvironmentUnit);
  const bool shades = context.method.shadesTranslucent(context.state);
  // Each translucent surface point's material (a candle's pool: the liquid's), when a method shades
  // them, and the flames a mirror-like translucent surface reflects.
  SlotTable slots;
  if (shades) {
    slots = translucentSlotTable(scene);
    setSlotUniforms(p, slots, false);
    setFlameMirrorUniforms(p, scene, flameSheets(scene, context.state.timeS, settings));
  }
  context.method.bindSurface(p, context, kFirstMethodUnit);

  context.target.framebuffer.bind();
  glViewport(0, 0, settings.width, settings.height);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glDisable(GL_CULL_FACE);
  p.use();
  for (const DrawItem& item : context.geometry.items()) {
    p.set("uModel", item.model);
    p.set("uNormalMatrix", item.normalMatrix);
    p.set("uAlbedo", item.albedo);
    const SceneObject& object = scene.objects[static_cast<std::size_t>(item.objectIndex)];
    const bool translucent = shades && object.translucent;
    p.set("uTranslucent", translucent ? 1 : 0);
    if (translucent) {
      p.set("uSlot", slots.objectSlot[static_cast<std::size_t>(item.objectIndex)]);
      context.method.bindSurfaceObject(p, context, item.objectIndex);
    }
    item.draw();
  }
  glDisable(GL_DEPTH_TEST);
  glBindVertexArray(0);
  glUseProgram(0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  if (context.countMapCoverage) countCoverage(context);  // sss.maps=auto: the maps' variant wrote the bins
}

void SurfacePass::countCoverage(const FrameContext& context) {
  constexpr GLuint kGroup = 16;  // shaders/maps/coverage_histogram.comp's local size
  const gpu::Texture& bins = context.target.coverageBins;
  coverageHistogram_.use();
  bins.bind(0);
  coverageHistogram_.set("uCoverageBins", 0);
  glDispatchCompute((static_cast<GLuint>(bins.width()) + kGroup - 1) / kGroup,
                    (static_cast<GLuint>(bins.height()) + kGroup - 1) / kGroup, 1);
  glBindTextureUnit(0, 0);
  glUseProgram(0);
}

}  // namespace tallow::sss
