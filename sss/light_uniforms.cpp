#include "sss/light_uniforms.h"

#include <vector>

namespace tallow::sss {

void setLightUniforms(gpu::Program& p, const Scene& scene, const RenderSettings& settings, const ShadowPass& shadows,
                      GLuint directionalShadowUnit, GLuint pointShadowUnit) {
  std::vector<glm::vec3> dirDirection, dirIrradiance, pointPosition, pointIntensity;
  std::vector<int> dirLayer, pointLayer;
  std::vector<glm::mat4> dirMatrix;
  std::vector<float> dirTexel, pointRange;
  const ShadowLayers& layers = shadows.layers();
  // The shadow maps are kept between frames; a light's layer counts only while it casts shadows now.
  const auto castsShadow = [&](const Light& l) { return settings.shadows && l.castsShadows; };
  for (std::size_t i = 0; i < scene.lights.size(); ++i) {
    const Light& l = scene.lights[i];
    if (l.kind == LightKind::Directional) {
      dirDirection.push_back(glm::normalize(l.direction));
      dirIrradiance.push_back(l.intensity);
      const bool shadowed = castsShadow(l) && i < layers.directionalLayer.size() && layers.directionalLayer[i] >= 0;
      dirLayer.push_back(shadowed ? layers.directionalLayer[i] : -1);
      dirMatrix.push_back(shadowed ? layers.directionalMatrix[i] : glm::mat4(1.0f));
      dirTexel.push_back(shadowed ? layers.directionalTexel[i] : 0.0f);
    } else {
      pointPosition.push_back(l.position);
      pointIntensity.push_back(l.intensity);
      const bool shadowed = castsShadow(l) && i < layers.pointCube.size() && layers.pointCube[i] >= 0;
      pointLayer.push_back(shadowed ? layers.pointCube[i] : -1);
      pointRange.push_back(shadowed ? layers.pointRange[i] : 1.0f);
    }
  }
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
  p.set("uDirShadow", static_cast<int>(directionalShadowUnit));
  p.set("uPointShadow", static_cast<int>(pointShadowUnit));
  shadows.bind(directionalShadowUnit, pointShadowUnit);
}

int pointLightUniformIndex(const Scene& scene, std::size_t light) {
  int index = 0;
  for (std::size_t l = 0; l < light; ++l) index += scene.lights[l].kind == LightKind::Point ? 1 : 0;
  return index;
}

void setCameraUniforms(gpu::Program& program, const CameraView& camera) {
  program.set("uViewProjection", camera.viewProjection);
  program.set("uCameraPosition", camera.position);
  program.set("uCameraForward", camera.forward);
  program.set("uCameraOrthographic", camera.orthographic ? 1 : 0);
}

}  // namespace tallow::sss
