#include "sss/surface_pass.h"

#include "gpu/hdr_io.h"
#include "sss/light_uniforms.h"

namespace tallow::sss {
namespace {
constexpr GLuint kDirectionalShadowUnit = 0;
constexpr GLuint kPointShadowUnit = 1;
constexpr GLuint kMapsUnit = 2;
constexpr GLuint kMapDepthUnit = 3;
constexpr GLuint kEnvironmentUnit = 6;
constexpr GLuint kGatherFirstUnit = 7;  // the light G-buffers of the no-cache gather: 7 … 10
constexpr GLuint kVplShadowUnit = 11;
constexpr GLuint kSslpvFirstUnit = 12;       // SSLPV's accumulation grids and medium: 12 … 15
constexpr GLuint kImageSpaceFirstUnit = 16;  // the image-space accumulation: 16, 17

}  // namespace

SurfacePass::SurfacePass(const gpu::ShaderLibrary& shaders)
    : program_(shaders, {{{GL_VERTEX_SHADER, "surface.vert"}, {GL_FRAGMENT_SHADER, "surface.frag"}}}) {}

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

void SurfacePass::render(const Scene& scene, const RenderSettings& settings, const SceneGeometry& geometry,
                         const CameraView& camera, const ShadowPass& shadows, const TranslucentSource& source,
                         const VirtualPointLights* vpls, int frame, const gpu::Framebuffer& target, int width,
                         int height) {
  const RadiosityMaps* maps = source.maps;
  const RadiosityMaps* noCache = source.noCache;
  auto& p = program_;
  setLightUniforms(p, scene, settings, shadows, kDirectionalShadowUnit, kPointShadowUnit);
  p.set("uAmbient", scene.ambient);
  setCameraUniforms(p, camera);
  p.set("uSpecular", settings.specular ? 1 : 0);
  p.set("uEnvironment", environment_.id() ? 1 : 0);
  p.set("uEnvMap", static_cast<int>(kEnvironmentUnit));
  p.set("uEnvRotation", glm::radians(environmentRotationDeg_));
  p.set("uEnvScale", environmentScale_);
  if (environment_.id()) environment_.bind(kEnvironmentUnit);
  p.set("uNoCache", noCache ? 1 : 0);
  // The gather's samplers on their own units even when unused: a sampler left on unit 0 would clash
  // with the shadow map's type there and void every draw.
  p.set("uSssDirPosition", static_cast<int>(kGatherFirstUnit));
  p.set("uSssDirNormal", static_cast<int>(kGatherFirstUnit + 1));
  p.set("uSssPointGPosition", static_cast<int>(kGatherFirstUnit + 2));
  p.set("uSssPointGNormal", static_cast<int>(kGatherFirstUnit + 3));
  if (noCache) noCache->setGatherUniforms(p, scene, settings, kGatherFirstUnit, frame);
  if (maps) {
    maps->setAlgorithm1Uniforms(p, settings, kMapsUnit, kMapDepthUnit);
  } else {
    p.set("uMaps", static_cast<int>(kMapsUnit));
    p.set("uMapDepth", static_cast<int>(kMapDepthUnit));
    p.set("uMapCount", 0);
  }
  VirtualPointLights::setReceiverUniforms(p, vpls, kVplShadowUnit);
  p.set("uImageSpace", source.imageSpace ? 1 : 0);
  ImageSpaceSss::setSurfaceUniforms(p, source.imageSpace, settings, kImageSpaceFirstUnit);
  if (source.sslpv) source.sslpv->setLookupUniforms(p, settings, kSslpvFirstUnit);
  else Sslpv::setLookupOff(p, kSslpvFirstUnit);

  target.bind();
  glViewport(0, 0, width, height);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glDisable(GL_CULL_FACE);
  p.use();
  for (const DrawItem& item : geometry.items()) {
    p.set("uModel", item.model);
    p.set("uNormalMatrix", item.normalMatrix);
    p.set("uAlbedo", item.albedo);
    const SceneObject& object = scene.objects[static_cast<std::size_t>(item.objectIndex)];
    p.set("uTranslucent", source.any() && object.translucent ? 1 : 0);
    if (noCache && object.translucent) p.set("uSlot", noCache->slots()[static_cast<std::size_t>(item.objectIndex)]);
    p.set("uObjectEta", object.material.eta);
    item.draw();
  }
  glDisable(GL_DEPTH_TEST);
  glBindVertexArray(0);
  glUseProgram(0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

}  // namespace tallow::sss
