#include "sss/maps/radiosity_maps.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "gpu/gl_limits.h"
#include "sss/maps/gbuffer_formats.h"
#include "sss/maps/layered_program.h"
#include "sss/maps/map_count.h"
#include "sss/maps/map_history.h"
#include "sss/maps/map_resolution.h"
#include "sss/maps/radiosity_estimator.h"
#include "sss/memory_budget.h"
#include "sss/view_setup.h"

namespace tallow::sss {
namespace {

constexpr GLuint kLayerViewsBinding = 4;  // maps/layered.vert or .geom (layered_program.h)
constexpr GLuint kCoveredTexelsBinding = 10;  // maps/covered_texels.glsl
std::atomic<bool> compactedHistoryAllowed{true};


const glm::mat4 kToTexture =
    glm::translate(glm::mat4(1.0f), glm::vec3(0.5f)) * glm::scale(glm::mat4(1.0f), glm::vec3(0.5f));

int mipLevels(int size) { return static_cast<int>(std::floor(std::log2(static_cast<double>(size)))) + 1; }

/// An orthonormal basis of the plane with normal `w`.
void planeBasis(const glm::vec3& w, glm::vec3& t1, glm::vec3& t2) {
  const glm::vec3 helper = std::abs(w.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
  t1 = glm::normalize(glm::cross(helper, w));
  t2 = glm::cross(w, t1);
}

/// GL state of the layered passes, restored to the defaults at the end of the scope.
struct LayeredState {
  LayeredState() {
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
  }
  ~LayeredState() {
    glDisable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glBindVertexArray(0);
    glUseProgram(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
  }
};

gpu::Texture colourArray(GLenum format, int size, int layers, int levels = 1) {
  gpu::Texture t = gpu::Texture::create2DArray(format, size, size, layers, levels);
  t.setFilter(levels > 1 ? GL_LINEAR_MIPMAP_LINEAR : GL_NEAREST, levels > 1 ? GL_LINEAR : GL_NEAREST);
  t.setWrap(GL_CLAMP_TO_EDGE);
  return t;
}

gpu::Texture cubeArray(GLenum format, int size, int cubes) {
  gpu::Texture t = gpu::Texture::createCubeArray(format, size, cubes);
  t.setFilter(GL_NEAREST, GL_NEAREST);
  t.setWrap(GL_CLAMP_TO_EDGE);
  return t;
}

}  // namespace

std::vector<MapView> radiosityMapViews(const std::vector<glm::vec3>& directions, const glm::vec3& centre, float radius) {
  std::vector<MapView> views;
  const float r = std::max(radius, 1e-6f);
  for (const glm::vec3& d : directions) {
    MapView v;
    v.direction = glm::normalize(d);
    const glm::vec3 eye = centre + v.direction * (2.0f * r);
    const glm::vec3 up = std::abs(v.direction.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    const glm::mat4 view = glm::lookAt(eye, centre, up);
    const glm::mat4 projection = glm::ortho(-r, r, -r, r, r, 3.0f * r);  // the sphere spans [r, 3r]
    v.viewProjection = projection * view;
    v.toTexture = kToTexture * v.viewProjection;
    views.push_back(v);
  }
  return views;
}

std::vector<MapView> radiosityMapViews(int k, const glm::vec3& centre, float radius) {
  std::vector<glm::vec3> directions;
  for (int i = 0; i < k; ++i) directions.emplace_back(haltonDirection<double>(static_cast<std::uint32_t>(i)));
  return radiosityMapViews(directions, centre, radius);
}

void drawTranslucentLayered(gpu::Program& program, const SceneGeometry& geometry, const std::vector<int>& slots,
                            const gpu::Buffer& layerViews, int instances) {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLayerViewsBinding, layerViews.id());
  program.set("uLayerBase", 0);
  for (const DrawItem& item : geometry.items()) {
    const int slot = slots[static_cast<std::size_t>(item.objectIndex)];
    if (slot < 0) continue;
    program.set("uModel", item.model);
    program.set("uNormalMatrix", item.normalMatrix);
    program.set("uSlot", slot);
    item.draw(instances);
  }
}

int mapCount(const Scene& scene, const RenderSettings& settings) {
  if (!scene.mapDirections.empty()) return static_cast<int>(scene.mapDirections.size());
  // Auto before the renderer chose (limits, memory budget): the most it may choose.
  return settings.sss.maps == kAuto ? kAutoMapsMax : settings.sss.maps;
}

BoundingSphere translucentBounds(const Scene& scene, const SceneGeometry& geometry) {
  geometry::Aabb box;
  for (const DrawItem& item : geometry.items()) {
    if (!scene.objects[static_cast<std::size_t>(item.objectIndex)].translucent || item.worldBounds.empty()) continue;
    box.extend(item.worldBounds.min);
    box.extend(item.worldBounds.max);
  }
  BoundingSphere s;
  if (box.empty()) return s;
  s.centre = box.centre();
  s.radius = 0.5f * glm::length(box.size());
  return s;
}

std::vector<PearlingWarning> pearlingWarnings(const Scene& scene, float sphereRadius, int lightMapSize) {
  std::vector<PearlingWarning> out;
  // A directional G-buffer spans the bounding sphere's diameter (directionalShadowViewProjection).
  const double texelMm = 2.0 * static_cast<double>(sphereRadius) * 1000.0 / std::max(lightMapSize, 1);
  for (const SceneObject& o : scene.objects) {
    if (!o.translucent) continue;
    const Material& m = o.material;
    for (int c = 0; c < 3; ++c) {
      const double sigmaTr = samplingSigmaTr(m.sigma_a[c], m.sigma_s[c], m.g[c], m.eta);
      if (1.0 / sigmaTr < texelMm) out.push_back({o.name, c, 1.0 / sigmaTr, texelMm});
    }
  }
  return out;
}

int effectiveLightMapSize(const Scene& scene, const RenderSettings& settings, float sphereRadius, int maxSize) {
  const double shortest = shortestDiffusionLengthMm(scene);  // mm
  const double diameterMm = 2.0 * static_cast<double>(sphereRadius) * 1000.0;
  const bool point = std::any_of(scene.lights.begin(), scene.lights.end(),
                                 [](const Light& l) { return l.kind == LightKind::Point; });
  int size = settings.sss.lightMapSize == kAuto ? autoLightMapSize(diameterMm, shortest, point, maxSize)
                                                : settings.sss.lightMapSize;
  if (!settings.sss.lightMapAuto) return size;
  const int cap = std::min(maxSize, 8192);
  while (size < cap && diameterMm / size > shortest) size *= 2;
  return std::min(size, cap);
}

RadiosityMaps::RadiosityMaps(const gpu::ShaderLibrary& shaders)
    : gbufferProgram_(shaders, layeredProgram("maps/light_gbuffer.frag")),
      depthProgram_(shaders, layeredProgram("maps/map_depth.frag")),
      mapProgram_(shaders, layeredProgram("maps/radiosity_map.frag")),
      mapGBufferProgram_(shaders, layeredProgram("maps/map_gbuffer.frag")),
      mapCompute_(shaders, {{{GL_COMPUTE_SHADER, "maps/radiosity_map.comp"}}}),
      historyCompute_(shaders, {{{GL_COMPUTE_SHADER, "maps/history.comp"}}}),
      historyMerge_(shaders, {{{GL_COMPUTE_SHADER, "maps/history_merge.comp"}}}),
      historyFade_(shaders, {{{GL_COMPUTE_SHADER, "maps/history_fade.comp"}}}),
      coveredTexelsCompute_(shaders, {{{GL_COMPUTE_SHADER, "maps/covered_texels.comp"}}}),
      dummyDir_(colourArray(GL_RGBA32F, 1, 1)),
      dummyPoint_(cubeArray(GL_RGBA32F, 1, 1)) {
  const float zero[4] = {0, 0, 0, 0};
  glClearTexImage(dummyDir_.id(), 0, GL_RGBA, GL_FLOAT, zero);
  glClearTexImage(dummyPoint_.id(), 0, GL_RGBA, GL_FLOAT, zero);
}

bool RadiosityMaps::applies(const Scene& scene, const RenderSettings& settings) {
  return settings.sss.method == SssMethod::RadiosityMaps && needsLightGBuffers(scene, settings);
}

bool RadiosityMaps::needsLightGBuffers(const Scene& scene, const RenderSettings& settings) {
  return (settings.sss.method == SssMethod::RadiosityMaps || settings.sss.method == SssMethod::NoCache) &&
         std::any_of(scene.objects.begin(), scene.objects.end(), [](const SceneObject& o) { return o.translucent; });
}

void RadiosityMaps::checkLimits(const Scene& scene, const RenderSettings& settings) {
  if (!needsLightGBuffers(scene, settings)) return;
  const SssSettings& s = settings.sss;
  translucentSlotTable(scene);  // throws when the objects (and their pools) need more slots than the passes hold
  int dir = 0, point = 0;
  for (const Light& l : scene.lights) (l.kind == LightKind::Directional ? dir : point)++;
  if (dir > kMaxSssDirectionalLights || point > kMaxSssPointLights)
    throw std::invalid_argument("the radiosity maps take at most " + std::to_string(kMaxSssDirectionalLights) +
                                " directional and " + std::to_string(kMaxSssPointLights) + " point lights");
  const gpu::GlLimits& limits = gpu::glLimits();
  const GLint maxLayers = limits.maxArrayTextureLayers, maxTexture = limits.maxTextureSize,
              maxCube = limits.maxCubeMapTextureSize;
  const int k = mapCount(scene, settings);
  if (k > maxLayers)
    throw std::invalid_argument("sss.maps: " + std::to_string(k) + " maps exceed this GPU's "
                                "GL_MAX_ARRAY_TEXTURE_LAYERS of " + std::to_string(maxLayers));
  if (s.mapSize > maxTexture)
    throw std::invalid_argument("sss.map_size: " + std::to_string(s.mapSize) + " exceeds this GPU's GL_MAX_TEXTURE_SIZE of " +
                                std::to_string(maxTexture));
  if (s.lightMapSize > maxTexture || (point > 0 && s.lightMapSize > maxCube)) {
    const bool texture = s.lightMapSize > maxTexture;
    std::string limit = texture ? "GL_MAX_TEXTURE_SIZE of " : "GL_MAX_CUBE_MAP_TEXTURE_SIZE of ";
    limit += std::to_string(texture ? maxTexture : maxCube);
    throw std::invalid_argument("sss.light_map_size: " + std::to_string(s.lightMapSize) + " exceeds this GPU's " + limit);
  }
  if (6 * point > maxLayers)
    throw std::invalid_argument("too many point lights for this GPU's GL_MAX_ARRAY_TEXTURE_LAYERS");
  // Memory: sss::checkMemoryBudget counts the maps with everything else the frame allocates.
}

void RadiosityMaps::ensureLightTargets(int dirCount, int pointCount) {
  const int lightSize = lightMapSize_;
  if (dirCount > 0 && (!dirPosition_.id() || dirPosition_.width() != lightSize || dirPosition_.depth() != dirCount)) {
    dirPosition_ = colourArray(kGBufferPositionFormat, lightSize, dirCount);
    dirNormal_ = colourArray(gBufferNormalFormat(), lightSize, dirCount);
    dirDepth_ = gpu::Texture::create2DArray(GL_DEPTH_COMPONENT32F, lightSize, lightSize, dirCount);
  }
  if (pointCount > 0 &&
      (!pointPosition_.id() || pointPosition_.width() != lightSize || pointPosition_.depth() != 6 * pointCount)) {
    pointPosition_ = cubeArray(kGBufferPositionFormat, lightSize, pointCount);
    pointNormal_ = cubeArray(gBufferNormalFormat(), lightSize, pointCount);
    pointDepth_ = gpu::Texture::createCubeArray(GL_DEPTH_COMPONENT32F, lightSize, pointCount);
  }
}

void RadiosityMaps::ensureMapTargets(int k, int size) {
  if (k > 0 && (!maps_.id() || maps_.width() != size || maps_.depth() != k)) {
    maps_ = colourArray(GL_RGBA32F, size, k, mipLevels(size));
    mapDepth_ = gpu::Texture::create2DArray(GL_DEPTH_COMPONENT32F, size, size, k);
    mapDepth_.setFilter(GL_LINEAR, GL_LINEAR);  // bilinear comparison taps in Algorithm 1
    mapDepth_.setWrap(GL_CLAMP_TO_BORDER);
    mapDepth_.setBorderColor(0, 0, 0, 0);  // outside a map: not seen by it
    mapDepth_.setDepthCompare(true);
  }
}

void RadiosityMaps::renderLightGBuffers(const Scene& scene, const RenderSettings& settings,
                                        const SceneGeometry& geometry) {
  slotTable_ = translucentSlotTable(scene);
  sphere_ = translucentBounds(scene, geometry);
  shortestDiffusionMm_ = shortestDiffusionLengthMm(scene);
  const GLint maxTexture = gpu::glLimits().maxTextureSize, maxCube = gpu::glLimits().maxCubeMapTextureSize;
  lightMapSize_ = effectiveLightMapSize(scene, settings, sphere_.radius, std::min(maxTexture, maxCube));
  // sss.light_map_auto sizes the G-buffers from the geometry, so only now can the budget count them.
  if (lightMapSize_ != settings.sss.lightMapSize) checkMemoryBudget(scene, settings, lightMapSize_, mapSize_);

  std::vector<int> dirLights, pointLights;
  for (std::size_t i = 0; i < scene.lights.size(); ++i)
    (scene.lights[i].kind == LightKind::Directional ? dirLights : pointLights).push_back(static_cast<int>(i));
  ensureLightTargets(static_cast<int>(dirLights.size()), static_cast<int>(pointLights.size()));

  // Layer matrices: directional views fitted to the translucent objects (depth over the whole
  // scene, so occluders between the light and the object are in front), then point-light cubes.
  const int size = lightMapSize_;
  geometry::Aabb translucentBox;
  translucentBox.extend(sphere_.centre - glm::vec3(sphere_.radius));
  translucentBox.extend(sphere_.centre + glm::vec3(sphere_.radius));
  dirMatrices_.clear();
  dirTangent_.clear();
  dirBitangent_.clear();
  std::vector<glm::mat4> dirLayers, pointLayers;
  for (int i : dirLights) {
    const glm::vec3 w = glm::normalize(scene.lights[static_cast<std::size_t>(i)].direction);
    float texel = 0.0f;
    const glm::mat4 vp = directionalShadowViewProjection(w, translucentBox, geometry.worldBounds(), size, texel);
    dirLayers.push_back(vp);
    dirMatrices_.push_back(kToTexture * vp);
    glm::vec3 t1, t2;
    planeBasis(w, t1, t2);
    dirTangent_.push_back(t1);
    dirBitangent_.push_back(t2);
  }
  const geometry::Aabb world = geometry.worldBounds();
  for (int i : pointLights) {
    const glm::vec3 p = scene.lights[static_cast<std::size_t>(i)].position;
    float range = 1e-3f;
    for (int c = 0; c < 8; ++c) {
      const glm::vec3 corner((c & 1) ? world.max.x : world.min.x, (c & 2) ? world.max.y : world.min.y,
                             (c & 4) ? world.max.z : world.min.z);
      range = std::max(range, glm::length(corner - p) * 1.01f);
    }
    for (const glm::mat4& face : cubeFaceViewProjections(p, range * 1e-4f, range)) pointLayers.push_back(face);
  }

  LayeredState state;
  gbufferProgram_.use();
  setSlotUniforms(gbufferProgram_, slotTable_, false);
  glViewport(0, 0, size, size);
  const auto drawAll = [&](const std::vector<glm::mat4>& layers, gpu::Buffer& views) {
    views.assign(layers.size() * sizeof(glm::mat4), layers.data());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLayerViewsBinding, views.id());
    gbufferProgram_.set("uLayerBase", 0);
    for (const DrawItem& item : geometry.items()) {
      gbufferProgram_.set("uModel", item.model);
      gbufferProgram_.set("uNormalMatrix", item.normalMatrix);
      gbufferProgram_.set("uSlot", slotTable_.objectSlot[static_cast<std::size_t>(item.objectIndex)]);
      item.draw(static_cast<int>(layers.size()));
    }
  };
  const auto renderKind = [&](gpu::TargetFramebuffer& target, const gpu::Texture& position, const gpu::Texture& normal,
                              const gpu::Texture& depth, const std::vector<glm::mat4>& layers, gpu::Buffer& views,
                              const char* what) {
    if (layers.empty()) return;
    gpu::bindGBuffer(target, position, normal, depth, 1.0f, what);  // position tag 0: nothing
    drawAll(layers, views);
  };
  renderKind(dirTarget_, dirPosition_, dirNormal_, dirDepth_, dirLayers, dirLayerViews_, "directional light G-buffer");
  renderKind(pointTarget_, pointPosition_, pointNormal_, pointDepth_, pointLayers, pointLayerViews_,
             "point light G-buffer");
}

void RadiosityMaps::setLightUniforms(gpu::Program& p, const Scene& scene, GLuint firstUnit) const {
  const GLuint kDirPositionUnit = firstUnit, kDirNormalUnit = firstUnit + 1, kPointPositionUnit = firstUnit + 2,
               kPointNormalUnit = firstUnit + 3;
  std::vector<glm::vec3> dirDirection, dirIrradiance, pointPosition, pointIntensity;
  for (const Light& l : scene.lights) {
    if (l.kind == LightKind::Directional) {
      dirDirection.push_back(glm::normalize(l.direction));
      dirIrradiance.push_back(l.intensity);
    } else {
      pointPosition.push_back(l.position);
      pointIntensity.push_back(l.intensity);
    }
  }
  const int nd = static_cast<int>(dirDirection.size()), np = static_cast<int>(pointPosition.size());
  p.set("uSssDirCount", nd);
  p.set("uSssPointCount", np);
  if (nd > 0) {
    p.set("uSssDirDirection", dirDirection.data(), nd);
    p.set("uSssDirIrradiance", dirIrradiance.data(), nd);
    p.set("uSssDirMatrix", dirMatrices_.data(), nd);
    p.set("uSssDirTangent", dirTangent_.data(), nd);
    p.set("uSssDirBitangent", dirBitangent_.data(), nd);
  }
  if (np > 0) {
    p.set("uSssPointPosition", pointPosition.data(), np);
    p.set("uSssPointIntensity", pointIntensity.data(), np);
  }
  p.set("uSssDirPosition", static_cast<int>(kDirPositionUnit));
  p.set("uSssDirNormal", static_cast<int>(kDirNormalUnit));
  p.set("uSssPointGPosition", static_cast<int>(kPointPositionUnit));
  p.set("uSssPointGNormal", static_cast<int>(kPointNormalUnit));
  (nd > 0 ? dirPosition_ : dummyDir_).bind(kDirPositionUnit);
  (nd > 0 ? dirNormal_ : dummyDir_).bind(kDirNormalUnit);
  (np > 0 ? pointPosition_ : dummyPoint_).bind(kPointPositionUnit);
  (np > 0 ? pointNormal_ : dummyPoint_).bind(kPointNormalUnit);
}

void setSlotMaterialUniforms(gpu::Program& p, const Scene& scene, const std::vector<int>& slots) {
  // Unused slots get a harmless medium (σ_s = 1, η = 1) so that no shader divides by zero.
  std::vector<glm::vec3> sigmaA(kMaxTranslucentObjects, glm::vec3(0.0f)), sigmaS(kMaxTranslucentObjects, glm::vec3(1.0f)),
      g(kMaxTranslucentObjects, glm::vec3(0.0f));
  std::vector<float> eta(kMaxTranslucentObjects, 1.0f);
  for (std::size_t i = 0; i < scene.objects.size() && i < slots.size(); ++i) {
    const int slot = slots[i];
    if (slot < 0) continue;
    const Material& m = scene.objects[i].material;
    sigmaA[static_cast<std::size_t>(slot)] = m.sigma_a;
    sigmaS[static_cast<std::size_t>(slot)] = m.sigma_s;
    g[static_cast<std::size_t>(slot)] = m.g;
    eta[static_cast<std::size_t>(slot)] = m.eta;
  }
  p.set("uSigmaA", sigmaA.data(), kMaxTranslucentObjects);
  p.set("uSigmaS", sigmaS.data(), kMaxTranslucentObjects);
  p.set("uG", g.data(), kMaxTranslucentObjects);
  glProgramUniform1fv(p.id(), p.location("uEta"), kMaxTranslucentObjects, eta.data());
}

void RadiosityMaps::setGatherUniforms(gpu::Program& p, const Scene& scene, const RenderSettings& settings,
                                      GLuint firstUnit, int frame) const {
  const SssSettings& s = settings.sss;
  setLightUniforms(p, scene, firstUnit);
  setSlotUniforms(p, slotTable_, true);
  p.set("uBssrdfModel", static_cast<int>(s.model));
  p.set("uSamples", s.samples);
  p.set("uFrame", frame);
  p.set("uStereographic", s.stereographic ? 1 : 0);
  p.set("uProjectedArea", s.projectedArea ? 1 : 0);
  p.set("uTexelPlane", s.texelPlane ? 1 : 0);
  p.set("uPointShare", s.pointShare);
}

void RadiosityMaps::setAlgorithm1Uniforms(gpu::Program& p, const RenderSettings& settings, GLuint mapsUnit,
                                          GLuint depthUnit, bool pixelLookups, bool countVplCoverage) const {
  constexpr GLuint kMapViewsBinding = 5;  // shaders/maps/algorithm1.glsl
  // ε_bias and ε_comb are relative to the translucent objects' bounding radius (sss.bias, sss.comb).
  const float radius = sphere_.radius;
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kMapViewsBinding, cameraViews_.id());
  p.set("uMaxFootprint", pixelLookups ? maxMapFootprint(shortestDiffusionMm_, viewSphere_.radius) : 1e30f);
  p.set("uNarrowFootprint", pixelLookups ? 1 : 0);
  p.set("uMapCount", static_cast<int>(views_.size()));
  p.set("uEpsBias", settings.sss.bias * radius);
  p.set("uEpsComb", settings.sss.comb * radius);
  p.set("uViewWeight", settings.sss.viewWeight);
  p.set("uCountVplCoverage", countVplCoverage ? 1 : 0);
  p.set("uMaps", static_cast<int>(mapsUnit));
  p.set("uMapDepth", static_cast<int>(depthUnit));
  maps_.bind(mapsUnit);
  mapDepth_.bind(depthUnit);
}

bool RadiosityMaps::viewsHold(const BoundingSphere& sphere) const {
  // The views enclose viewSphere_; a sphere inside it is seen whole by the same texels' rays.
  return glm::length(sphere.centre - viewSphere_.centre) + sphere.radius <= viewSphere_.radius;
}

void RadiosityMaps::renderMaps(const Scene& scene, const RenderSettings& settings, const SceneGeometry& geometry,
                               MapsUpdate update) {
  const SssSettings& s = settings.sss;
  const int k = mapCount(scene, settings);
  // sss.map_size=auto is chosen at a restart (from the camera then), and kept while the maps
  // accumulate or reuse their history: a camera move alone never restarts them.
  if (update == MapsUpdate::Restart || frames_ == 0 || mapSize_ == 0) {
    mapSize_ = s.mapSize;
    if (s.mapSize == kAuto) {
      const GLint maxTexture = gpu::glLimits().maxTextureSize;
      const double pixels = projectedDiameterPixels(scene.camera, settings.height, sphere_);
      mapSize_ = autoMapSize(2.0 * sphere_.radius * 1000.0, shortestDiffusionMm_, pixels, maxTexture);
      if (mapSize_ != maps_.width()) checkMemoryBudget(scene, settings, lightMapSize_, mapSize_);
    }
  }
  const int size = mapSize_;
  const bool history = s.history > 0;
  // Resize keeps maps made for these views at this size; not while a still's fade is under way (its
  // source is per map, and the kept maps would hold what is left of the lagged frames for good).
  if (update == MapsUpdate::Resize && (frames_ == 0 || !viewsHold(sphere_) || maps_.width() != size ||
                                       views_.empty() || !maps_.id() || fadeFrames_ > 0))
    update = MapsUpdate::Restart;
  // Reuse needs the views it was made with and the last frame's G-buffer at this K and size.
  if (update == MapsUpdate::Reuse &&
      (!history || frames_ == 0 || !viewsHold(sphere_) || views_.size() != static_cast<std::size_t>(k) ||
       maps_.width() != size || !previousPosition_.id()))
    update = MapsUpdate::Restart;
  if (update == MapsUpdate::Restart) {
    frames_ = 0;
    seed_ = 0;
  }
  if (update != MapsUpdate::Accumulate) fadeFrames_ = 0;  // a fade in progress ends with the still
  if (update != MapsUpdate::Accumulate) mapsListed_ = false;  // a merge below lists them again
  // The first frame of a still after motion: the kept frames start to fade, and the count and the
  // seeds start over as a restart at the pause would (its frames then match this still's).
  const bool stillAfterMotion = update == MapsUpdate::Accumulate && lastUpdate_ == MapsUpdate::Reuse && history &&
                                frames_ > 0;
  lastUpdate_ = update;
  // Resize: the kept maps' sums, copied into the new array below (level 0; the mipmaps follow).
  gpu::Texture keptMaps;
  int keptLayers = 0;
  if (update == MapsUpdate::Resize) {
    keptLayers = std::min(k, maps_.depth());
    keptMaps = std::move(maps_);
    maps_ = gpu::Texture();
    frames_ = 0;
  }
  const bool resize = keptLayers > 0;
  const bool fresh = frames_ == 0;  // new views, maps emptied (a resize then copies the kept ones back)
  ensureMapTargets(k, size);
  const bool compute = s.computeGather;
  // The maps' G-buffer (x_o, n_o per texel, with depth): the compute gather's input, and what the
  // history compares frame to frame.
  const bool gbuffer = compute || history;
  LayeredState state;
  glViewport(0, 0, size, size);
  const auto drawTranslucent = [&](gpu::Program& program) {
    drawTranslucentLayered(program, geometry, slotTable_.objectSlot, mapLayerViews_, k);
  };
  const float zero[4] = {0, 0, 0, 0};
  const float one = 1.0f;
  const auto drawMapGBuffer = [&] {
    if (!mapPosition_.id() || mapPosition_.width() != size || mapPosition_.depth() != k) {
      for (gpu::TargetFramebuffer& t : mapGBufferTargets_) t.release();  // none keeps the old G-buffer
      mapPosition_ = colourArray(kGBufferPositionFormat, size, k);
      mapNormal_ = colourArray(kMapGBufferNormalFormat, size, k);
    }
    if (history && (!previousPosition_.id() || previousPosition_.width() != size || previousPosition_.depth() != k)) {
      previousPosition_ = colourArray(kGBufferPositionFormat, size, k);
      previousNormal_ = colourArray(kMapGBufferNormalFormat, size, k);
      // With the last frame's G-buffer, so that the first reuse allocates nothing the memory budget
      // (radiosityMapBytes) did not count from the start.
      historyMean_ = colourArray(GL_RGBA32F, size, k, mipLevels(size));
      historyFresh_ = colourArray(GL_RGBA32F, size, k, mipLevels(size));
      const std::size_t listBytes = coveredTexelBytes(size, k);
      coveredTexels_ = listBytes > 0 ? gpu::Buffer(listBytes) : gpu::Buffer();
    }
    if (!history) {
      previousPosition_ = gpu::Texture();
      previousNormal_ = gpu::Texture();
      historyMean_ = gpu::Texture();
      historyFresh_ = gpu::Texture();
      coveredTexels_ = gpu::Buffer();
    }
    gpu::bindGBuffer(mapGBufferTargets_[mapGBufferSide_], mapPosition_, mapNormal_, mapDepth_, 1.0f,
                     "scattered radiosity maps' G-buffer");
    mapGBufferProgram_.use();
    setSlotUniforms(mapGBufferProgram_, slotTable_, false);
    drawTranslucent(mapGBufferProgram_);
  };

  const bool reuse = !fresh && update == MapsUpdate::Reuse;
  if (reuse) {
    // Same views: the new G-buffer beside the last one, then each texel's sum kept, trimmed to
    // sss.history − 1 frames or reset (maps/history.comp) into historyMean_, and the maps emptied
    // for this frame's estimate; mergeHistory adds the two back after the gather.
    std::swap(mapPosition_, previousPosition_);
    std::swap(mapNormal_, previousNormal_);
    mapGBufferSide_ ^= 1;  // the other pair's target: attached to it already, nothing re-pointed
    drawMapGBuffer();
    compacted_ = listCoveredTexels(size, k);
    const HistoryTolerance tolerance = historyTolerance(scene, s.historyMove);
    gpu::Program& p = historyCompute_;
    p.use();
    p.set("uCompacted", compacted_ ? 1 : 0);
    constexpr GLuint kOldPosition = 0, kOldNormal = 1, kNewPosition = 2, kNewNormal = 3;
    p.set("uOldPosition", static_cast<int>(kOldPosition));
    p.set("uOldNormal", static_cast<int>(kOldNormal));
    p.set("uNewPosition", static_cast<int>(kNewPosition));
    p.set("uNewNormal", static_cast<int>(kNewNormal));
    p.set("uHistoryFrames", static_cast<float>(s.history));
    p.set("uMaxMove", tolerance.maxMoveM);
    p.set("uMinCos", tolerance.minCos);
    previousPosition_.bind(kOldPosition);
    previousNormal_.bind(kOldNormal);
    mapPosition_.bind(kNewPosition);
    mapNormal_.bind(kNewNormal);
    glBindImageTexture(0, maps_.id(), 0, GL_TRUE, 0, GL_READ_WRITE, GL_RGBA32F);
    glBindImageTexture(1, historyMean_.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    dispatchHistory(size, k, compacted_);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT |
                    GL_FRAMEBUFFER_BARRIER_BIT);
    frames_ = std::min(frames_, s.history - 1);
  }

  if (fresh) {
    if (!resize) viewSphere_ = sphere_;  // a resize keeps the kept maps' views
    views_ = scene.mapDirections.empty() ? radiosityMapViews(k, viewSphere_.centre, viewSphere_.radius)
                                         : radiosityMapViews(scene.mapDirections, viewSphere_.centre, viewSphere_.radius);
    std::vector<glm::mat4> layers;
    // algorithm1.glsl's MapViewGpu; the orthographic depth spans 2·radius (radiosityMapViews).
    struct CameraView {
      glm::mat4 toTexture;
      glm::vec4 direction, depthScale;
    };
    std::vector<CameraView> camera;
    const glm::vec4 depthPerMetre(0.5f / std::max(sphere_.radius, 1e-9f));
    for (const MapView& v : views_) {
      layers.push_back(v.viewProjection);
      camera.push_back({v.toTexture, glm::vec4(v.direction, 0.0f), depthPerMetre});
    }
    mapLayerViews_.assign(layers.size() * sizeof(glm::mat4), layers.data());
    cameraViews_.assign(camera.size() * sizeof(CameraView), camera.data());
    glClearTexImage(maps_.id(), 0, GL_RGBA, GL_FLOAT, zero);
    if (resize)
      glCopyImageSubData(keptMaps.id(), GL_TEXTURE_2D_ARRAY, 0, 0, 0, 0, maps_.id(), GL_TEXTURE_2D_ARRAY, 0, 0, 0, 0,
                         size, size, keptLayers);
    if (gbuffer) {
      // The maps' G-buffer with depth: also the visibility of Algorithm 1.
      drawMapGBuffer();
    } else {
      // Depth pre-pass of the translucent objects into all K layers.
      const gpu::Framebuffer& fb = mapDepthTarget_.attach({}, {&mapDepth_}, "scattered radiosity maps' depth");
      glClearNamedFramebufferfv(fb.id(), GL_DEPTH, 0, &one);
      fb.bind();
      depthProgram_.use();
      drawTranslucent(depthProgram_);
    }
  }

  if (stillAfterMotion) {  // before this frame's samples, which stay
    startFade(s.frames);
    frames_ = 0;
    seed_ = 0;
  }

  if (compute) {
    gpu::Program& p = mapCompute_;
    p.use();
    setGatherUniforms(p, scene, settings, 0, seed_);
    constexpr GLuint kMapPositionUnit = 4, kMapNormalUnit = 5;
    p.set("uMapPosition", static_cast<int>(kMapPositionUnit));
    p.set("uMapNormal", static_cast<int>(kMapNormalUnit));
    mapPosition_.bind(kMapPositionUnit);
    mapNormal_.bind(kMapNormalUnit);
    glBindImageTexture(0, maps_.id(), 0, GL_TRUE, 0, GL_READ_WRITE, GL_RGBA32F);
    const auto groups = static_cast<GLuint>((size + 7) / 8);
    glDispatchCompute(groups, groups, static_cast<GLuint>(k));
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
  } else {
    // Shading: the estimator once per visible texel, added to the frames before (Algorithm 1
    // divides by F).
    mapShadeTarget_.attach({{&maps_}}, {&mapDepth_}, "scattered radiosity maps").bind();
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    mapProgram_.use();
    setGatherUniforms(mapProgram_, scene, settings, 0, seed_);
    drawTranslucent(mapProgram_);
  }
  if (reuse) mergeHistory(settings);
  if (fadeFrames_ > 0) fade();
  ++frames_;
  ++seed_;
  glGenerateTextureMipmap(maps_.id());
}

void RadiosityMaps::mergeHistory(const RenderSettings& settings) {
  const int size = maps_.width(), k = maps_.depth();
  const bool rescale = settings.sss.historyRescale > 0.0f;
  gpu::Program& p = historyMerge_;
  p.use();
  const GLbitfield barrier =
      GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT;
  glMemoryBarrier(barrier | GL_FRAMEBUFFER_BARRIER_BIT);  // the fragment gather's blending
  glBindImageTexture(0, maps_.id(), 0, GL_TRUE, 0, GL_READ_WRITE, GL_RGBA32F);
  glBindImageTexture(1, historyMean_.id(), 0, GL_TRUE, 0, GL_READ_ONLY, GL_RGBA32F);
  glBindImageTexture(2, historyFresh_.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  p.set("uRescale", static_cast<int>(rescale));
  p.set("uCompacted", compacted_ ? 1 : 0);
  if (rescale) {
    p.set("uStage", 0);
    dispatchHistory(size, k, compacted_);
    glMemoryBarrier(barrier);
    const double spanMm = 2.0 * static_cast<double>(viewSphere_.radius) * 1000.0;
    const auto level =
        static_cast<float>(historyRescaleLevel(size, spanMm, shortestDiffusionMm_, settings.sss.historyRescale));
    // Only the levels the ratio reads (a trilinear look-up at uLevel: up to ⌈uLevel⌉), not the
    // whole chain; the look-up clamps to that level, which it never passes.
    const int top = std::clamp(static_cast<int>(std::ceil(level)), 0, historyMean_.levels() - 1);
    for (const gpu::Texture* t : {&historyMean_, &historyFresh_}) {
      glTextureParameteri(t->id(), GL_TEXTURE_MAX_LEVEL, top);
      glGenerateTextureMipmap(t->id());
    }
    constexpr GLuint kHistoryUnit = 0, kFreshUnit = 1;
    p.set("uHistoryMips", static_cast<int>(kHistoryUnit));
    p.set("uFreshMips", static_cast<int>(kFreshUnit));
    historyMean_.bind(kHistoryUnit);
    historyFresh_.bind(kFreshUnit);
    p.set("uLevel", level);
    p.set("uMaxRatio", kHistoryMaxRatio);
  }
  p.set("uStage", 1);
  dispatchHistory(size, k, compacted_);
  glMemoryBarrier(barrier);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCoveredTexelsBinding, 0);
  mapsListed_ = compacted_;
  compacted_ = false;
}

std::size_t coveredTexelBytes(int size, int k) {
  const std::uint64_t texels = std::uint64_t(size) * std::uint64_t(size) * std::uint64_t(k);
  return texels >= (std::uint64_t{1} << 32) ? 0 : static_cast<std::size_t>(16 + 4 * texels);
}

void RadiosityMaps::allowCompactedHistory(bool allow) { compactedHistoryAllowed.store(allow); }

bool RadiosityMaps::listCoveredTexels(int size, int k) {
  if (!compactedHistoryAllowed.load() || coveredTexels_.size() != coveredTexelBytes(size, k) ||
      coveredTexels_.size() == 0)
    return false;
  const GLuint header[4] = {0, 0, 1, 1};  // no texel yet; 0 × 1 × 1 groups
  coveredTexels_.upload(0, sizeof header, header);
  gpu::Program& p = coveredTexelsCompute_;
  p.use();
  constexpr GLuint kOld = 0, kNew = 1;
  p.set("uOldPosition", static_cast<int>(kOld));
  p.set("uNewPosition", static_cast<int>(kNew));
  previousPosition_.bind(kOld);
  mapPosition_.bind(kNew);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCoveredTexelsBinding, coveredTexels_.id());
  glMemoryBarrier(GL_FRAMEBUFFER_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);  // the G-buffer just drawn
  const auto groups = static_cast<GLuint>((size + 7) / 8);
  glDispatchCompute(groups, groups, static_cast<GLuint>(k));
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
  // The passes below write only the listed texels of these: the others hold 0, as the full
  // dispatch would have written there (no surface in either frame: nothing kept).
  const float zero[4] = {0, 0, 0, 0};
  glClearTexImage(historyMean_.id(), 0, GL_RGBA, GL_FLOAT, zero);
  glClearTexImage(historyFresh_.id(), 0, GL_RGBA, GL_FLOAT, zero);
  return true;
}

void RadiosityMaps::dispatchHistory(int size, int k, bool listed) const {
  if (!listed) {
    const auto groups = static_cast<GLuint>((size + 7) / 8);
    glDispatchCompute(groups, groups, static_cast<GLuint>(k));
    return;
  }
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, coveredTexels_.id());
  glDispatchComputeIndirect(sizeof(GLuint));  // coveredGroups
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
}

void RadiosityMaps::startFade(int frames) {
  // Before this frame's gather: the kept history and the last moving frame's samples.
  glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
  glCopyImageSubData(maps_.id(), GL_TEXTURE_2D_ARRAY, 0, 0, 0, 0, historyFresh_.id(), GL_TEXTURE_2D_ARRAY, 0, 0, 0, 0,
                     maps_.width(), maps_.height(), maps_.depth());
  fadeFrames_ = std::max(frames, 1);
  fadeDone_ = 0;
}

void RadiosityMaps::fade() {
  gpu::Program& p = historyFade_;
  p.use();
  p.set("uShare", 1.0f / static_cast<float>(fadeFrames_));
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
  glBindImageTexture(0, maps_.id(), 0, GL_TRUE, 0, GL_READ_WRITE, GL_RGBA32F);
  glBindImageTexture(1, historyFresh_.id(), 0, GL_TRUE, 0, GL_READ_ONLY, GL_RGBA32F);
  // What fades (the maps when the still began) lies where the last merge's list says: only there,
  // when it does (the list is left from the last moving frame; a still does not rebuild it).
  p.set("uCompacted", mapsListed_ ? 1 : 0);
  if (mapsListed_) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCoveredTexelsBinding, coveredTexels_.id());
  dispatchHistory(maps_.width(), maps_.depth(), mapsListed_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCoveredTexelsBinding, 0);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
  gpu::unbindComputeState(2, 0);
  if (++fadeDone_ == fadeFrames_) fadeFrames_ = 0;
}

std::size_t RadiosityMaps::bytes() const {
  return dirPosition_.bytes() + dirNormal_.bytes() + dirDepth_.bytes() + pointPosition_.bytes() +
         pointNormal_.bytes() + pointDepth_.bytes() + maps_.bytes() + mapDepth_.bytes() + mapPosition_.bytes() +
         mapNormal_.bytes() + previousPosition_.bytes() + previousNormal_.bytes() + historyMean_.bytes() +
         historyFresh_.bytes() + coveredTexels_.size();
}

}  // namespace tallow::sss
