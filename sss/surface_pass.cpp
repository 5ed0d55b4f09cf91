#include "sss/surface_pass.h"

#include <algorithm>
#include <vector>

#include "gpu/hdr_io.h"

namespace tallow::sss {
namespace {
constexpr GLuint kDirectionalShadowUnit = 0;
constexpr GLuint kPointShadowUnit = 1;
constexpr GLuint kMapsUnit = 2;
constexpr GLuint kMapDepthUnit = 3;
constexpr GLuint kEnvironmentUnit = 6;
constexpr GLuint kGatherFirstUnit = 7;  // the light G-buffers of the no-cache gather: 7 … 10
constexpr GLuint kVplShadowUnit = 11;
constexpr GLuint kSslpvFirstUnit = 12;  // SSLPV's accumulation grids and medium: 12 … 15

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
                         const CameraView& camera, const ShadowPass& shadows, const RadiosityMaps* maps,
                         const RadiosityMaps* noCache, const VirtualPointLights* vpls, int frame, const gpu::Framebuffer& target, int width,
                         int height, const Sslpv* sslpv) {
  // Lights into the shader's arrays.
  std::vector<glm::vec3> dirDirection, dirIrradiance, pointPosition, pointIntensity;
  std::vector<int> dirLayer, pointLayer;
  std::vector<glm::mat4> dirMatrix;
  std::vector<float> dirTexel, pointRange;
  const ShadowLayers& layers = shadows.layers();
  for (std::size_t i = 0; i < scene.lights.size(); ++i) {
    const Light& l = scene.lights[i];
    if (l.kind == LightKind::Directional) {
      dirDirection.push_back(glm::normalize(l.direction));
      dirIrradiance.push_back(l.intensity);
      const bool shadowed = i < layers.directionalLayer.size() && layers.directionalLayer[i] >= 0;
      dirLayer.push_back(shadowed ? layers.directionalLayer[i] : -1);
      dirMatrix.push_back(shadowed ? layers.directionalMatrix[i] : glm::mat4(1.0f));
      dirTexel.push_back(shadowed ? layers.directionalTexel[i] : 0.0f);
    } else {
      pointPosition.push_back(l.position);
      pointIntensity.push_back(l.intensity);
      const bool shadowed = i < layers.pointCube.size() && layers.pointCube[i] >= 0;
      pointLayer.push_back(shadowed ? layers.pointCube[i] : -1);
      pointRange.push_back(shadowed ? layers.pointRange[i] : 1.0f);
    }
  }
  auto& p = program_;
  p.set("uDirCount", static_cast<int>(dirDirection.size()));
  p.set("uPointCount", static_cast<int>(pointPosition.size()));
  if (!dirDirection.empty()) {
    const int n = static_cast<int>(dirDirection.size());
    p.set("uDirDirection", dirDirection.data(), n);
    p.set("uDirIrradiance", dirIrradiance.data(), n);
    p.set("uDirShadowMatrix", dirMatrix.data(), n);
    glProgramUniform1iv(p.id(), p.location("uDirShadowLayer"), n, dirLayer.data());
    glProgramUniform1fv(p.id(), p.location("uDirShadowTexel"), n, dirTexel.data());
  }
  if (!pointPosition.empty()) {
    const int n = static_cast<int>(pointPosition.size());
    p.set("uPointPosition", pointPosition.data(), n);
    p.set("uPointIntensity", pointIntensity.data(), n);
    glProgramUniform1iv(p.id(), p.location("uPointShadowLayer"), n, pointLayer.data());
    glProgramUniform1fv(p.id(), p.location("uPointShadowRange"), n, pointRange.data());
  }
  p.set("uPointShadowTexelAngle", layers.pointTexelAngle);
  p.set("uShadowBias", settings.shadowBias);
  p.set("uPcfRadius", settings.pcfRadius);
  p.set("uDirShadow", static_cast<int>(kDirectionalShadowUnit));
  p.set("uPointShadow", static_cast<int>(kPointShadowUnit));
  p.set("uAmbient", scene.ambient);
  p.set("uViewProjection", camera.viewProjection);
  p.set("uCameraPosition", camera.position);
  p.set("uCameraForward", camera.forward);
  p.set("uCameraOrthographic", camera.orthographic ? 1 : 0);
  shadows.bind(kDirectionalShadowUnit, kPointShadowUnit);
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
  if (sslpv) sslpv->setLookupUniforms(p, settings, kSslpvFirstUnit);
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
    p.set("uTranslucent", (maps || noCache || sslpv) && object.translucent ? 1 : 0);
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
