#include "sss/shadow_pass.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>

#include "gpu/glsl_shared.h"
#include "sss/view_setup.h"

namespace tallow::glsl {
#include "shaders/common/cube_shadow_depth.glsl"
}  // namespace tallow::glsl

namespace tallow::sss {
namespace {

using glsl::kCubeShadowNearFraction;  // the receivers' look-up assumes this near plane

gpu::Texture makeDepthTexture(bool cube, int size, int layers) {
  gpu::Texture t = cube ? gpu::Texture::createCubeArray(GL_DEPTH_COMPONENT32F, size, layers)
                        : gpu::Texture::create2DArray(GL_DEPTH_COMPONENT32F, size, size, layers);
  t.setFilter(GL_LINEAR, GL_LINEAR);  // bilinear PCF per comparison tap
  t.setWrap(GL_CLAMP_TO_BORDER);
  t.setBorderColor(1, 1, 1, 1);  // outside the map: lit
  t.setDepthCompare(true);
  return t;
}

/// Draws every shape with `viewProjection` into the bound framebuffer.
void drawDepth(gpu::Program& program, const SceneGeometry& geometry, const glm::mat4& viewProjection) {
  program.set("uLightViewProjection", viewProjection);
  for (const DrawItem& item : geometry.items()) {
    program.set("uModel", item.model);
    item.draw();
  }
}

/// Depth test and write on, no colour; restored to GL defaults at the end of the scope.
struct DepthOnlyState {
  DepthOnlyState() {
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
  }
  ~DepthOnlyState() {
    glDisable(GL_DEPTH_TEST);
    glBindVertexArray(0);
    glUseProgram(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
  }
};

}  // namespace

ShadowPass::ShadowPass(const gpu::ShaderLibrary& shaders)
    : program_(shaders, {{{GL_VERTEX_SHADER, "shadow_depth.vert"}}}),  // depth only: early depth kept
      dummyDirectional_(makeDepthTexture(false, 1, 1)),
      dummyPoint_(makeDepthTexture(true, 1, 1)) {
  const float one = 1.0f;
  glClearTexImage(dummyDirectional_.id(), 0, GL_DEPTH_COMPONENT, GL_FLOAT, &one);
  glClearTexImage(dummyPoint_.id(), 0, GL_DEPTH_COMPONENT, GL_FLOAT, &one);
}

bool ShadowPass::needsDirectional(const Scene& scene, const RenderSettings& settings) {
  return settings.shadows && std::any_of(scene.lights.begin(), scene.lights.end(), [](const Light& l) {
           return l.castsShadows && l.kind == LightKind::Directional;
         });
}

bool ShadowPass::needsPoint(const Scene& scene, const RenderSettings& settings) {
  return settings.shadows && std::any_of(scene.lights.begin(), scene.lights.end(), [](const Light& l) {
           return l.castsShadows && l.kind == LightKind::Point;
         });
}

void ShadowPass::reset(std::size_t lightCount) {
  resetDirectional(lightCount);
  resetPoint(lightCount);
}

void ShadowPass::resetDirectional(std::size_t lightCount) {
  layers_.directionalLayer.assign(lightCount, -1);
  layers_.directionalMatrix.assign(lightCount, glm::mat4(1.0f));
  layers_.directionalTexel.assign(lightCount, 0.0f);
}

void ShadowPass::resetPoint(std::size_t lightCount) {
  layers_.pointCube.assign(lightCount, -1);
  layers_.pointRange.assign(lightCount, 1.0f);
}

void ShadowPass::ensure(gpu::Texture& texture, std::vector<gpu::TargetFramebuffer>& targets, bool cube, int size,
                        int layers) {
  const int depth = cube ? 6 * layers : layers;
  if (texture.id() && texture.width() == size && texture.depth() == depth) return;
  for (gpu::TargetFramebuffer& t : targets) t.release();  // none keeps the old map alive
  targets.resize(static_cast<std::size_t>(depth));
  texture = makeDepthTexture(cube, size, layers);
}

void ShadowPass::renderDirectional(const Scene& scene, const RenderSettings& settings, const SceneGeometry& geometry) {
  const std::size_t n = scene.lights.size();
  resetDirectional(n);
  if (!needsDirectional(scene, settings)) return;
  int count = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (scene.lights[i].castsShadows && scene.lights[i].kind == LightKind::Directional)
      layers_.directionalLayer[i] = count++;
  const int size = settings.shadowMapSize;
  ensure(directional_, directionalTargets_, false, size, count);

  DepthOnlyState state;
  program_.use();
  program_.set("uLightOrigin", glm::vec3(0.0f));
  glViewport(0, 0, size, size);
  // [-1,1]³ → [0,1]³ for texture lookup.
  const glm::mat4 toTexture = glm::translate(glm::mat4(1.0f), glm::vec3(0.5f)) * glm::scale(glm::mat4(1.0f), glm::vec3(0.5f));
  for (std::size_t i = 0; i < n; ++i) {
    const int layer = layers_.directionalLayer[i];
    if (layer < 0) continue;
    directionalTargets_[static_cast<std::size_t>(layer)].attach({}, {&directional_, 0, layer}, "directional shadow map").bind();
    glClear(GL_DEPTH_BUFFER_BIT);
    float texel = 0.0f;
    const glm::mat4 vp = directionalShadowViewProjection(scene.lights[i].direction, geometry.casterBounds(),
                                                           geometry.worldBounds(), size, texel);
    drawDepth(program_, geometry, vp);
    layers_.directionalMatrix[i] = toTexture * vp;
    layers_.directionalTexel[i] = texel;
  }
}

void ShadowPass::renderPoint(const Scene& scene, const RenderSettings& settings, const SceneGeometry& geometry) {
  const std::size_t n = scene.lights.size();
  resetPoint(n);
  if (!needsPoint(scene, settings)) return;
  int count = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (scene.lights[i].castsShadows && scene.lights[i].kind == LightKind::Point) layers_.pointCube[i] = count++;
  // Cube faces are smaller than a directional map: each covers only a quarter of the view sphere
  // around the light, so half the size gives a similar texel density for nearby receivers.
  const int size = std::max(16, settings.shadowMapSize / 2);
  ensure(point_, pointTargets_, true, size, count);
  layers_.pointTexelAngle = glm::radians(90.0f) / static_cast<float>(size);

  DepthOnlyState state;
  program_.use();
  glViewport(0, 0, size, size);
  const geometry::Aabb bounds = geometry.worldBounds();
  for (std::size_t i = 0; i < n; ++i) {
    const int cube = layers_.pointCube[i];
    if (cube < 0) continue;
    const glm::vec3 p = scene.lights[i].position;
    // The range reaches the farthest corner of the scene's bounds.
    float range = 1e-3f;
    for (int c = 0; c < 8; ++c) {
      const glm::vec3 corner((c & 1) ? bounds.max.x : bounds.min.x, (c & 2) ? bounds.max.y : bounds.min.y,
                             (c & 4) ? bounds.max.z : bounds.min.z);
      range = std::max(range, glm::length(corner - p) * 1.01f);
    }
    layers_.pointRange[i] = range;
    // About the light (shadow_depth.vert subtracts its position first, as the receivers do).
    program_.set("uLightOrigin", p);
    const auto faces = cubeFaceViewProjections(glm::vec3(0.0f), range * kCubeShadowNearFraction, range);
    for (int f = 0; f < 6; ++f) {
      const int face = 6 * cube + f;
      pointTargets_[static_cast<std::size_t>(face)].attach({}, {&point_, 0, face}, "point shadow map").bind();
      glClear(GL_DEPTH_BUFFER_BIT);
      drawDepth(program_, geometry, faces[static_cast<std::size_t>(f)]);
    }
  }
}

void ShadowPass::bindPoint(GLuint pointUnit) const { (point_.id() ? point_ : dummyPoint_).bind(pointUnit); }

void ShadowPass::bind(GLuint directionalUnit, GLuint pointUnit) const {
  (directional_.id() ? directional_ : dummyDirectional_).bind(directionalUnit);
  (point_.id() ? point_ : dummyPoint_).bind(pointUnit);
}

}  // namespace tallow::sss
