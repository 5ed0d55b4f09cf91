#include "sss/maps/virtual_point_lights.h"

#include "sss/pass.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "gpu/gl_limits.h"
#include "sss/maps/gbuffer_formats.h"
#include "sss/maps/layered_program.h"
#include "sss/maps/radiosity_estimator.h"
#include "sss/view_setup.h"

namespace tallow::sss {
namespace {

constexpr GLuint kRecordsBinding = 6;     // maps/vpl.comp, maps/vpl_receiver.glsl
constexpr GLuint kDirectionsBinding = 7;  // maps/vpl.comp
constexpr GLuint kPartsBinding = 8;       // maps/vpl.comp, maps/vpl_receiver.glsl
constexpr GLuint kMapsUnit = 0, kMapDepthUnit = 1, kCubePositionUnit = 2, kCubeNormalUnit = 3;
/// A fixed start of the stable directions' Halton index, away from the maps' first directions.
constexpr int kStableFirst = 1024;

geometry::Aabb translucentBox(const Scene& scene, const SceneGeometry& geometry) {
  geometry::Aabb box;
  for (const DrawItem& item : geometry.items())
    if (scene.objects[static_cast<std::size_t>(item.objectIndex)].translucent && !item.worldBounds.empty()) {
      box.extend(item.worldBounds.min);
      box.extend(item.worldBounds.max);
    }
  return box;
}

bool anyOpaque(const Scene& scene) {
  return std::any_of(scene.objects.begin(), scene.objects.end(), [](const SceneObject& o) { return !o.translucent; });
}

/// GL state of the cube pass, restored to the defaults at the end of the scope.
struct CubePassState {
  CubePassState() {
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);  // keep the farthest surface from the centre: the outermost one
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
  }
  ~CubePassState() {
    glDisable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glBindVertexArray(0);
    glUseProgram(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
  }
};

}  // namespace

std::vector<glm::vec3> vplDirections(int count, int first) {
  std::vector<glm::vec3> out;
  out.reserve(static_cast<std::size_t>(std::max(count, 0)));
  for (int i = 0; i < count; ++i) out.emplace_back(haltonDirection<double>(static_cast<std::uint32_t>(first + i)));
  return out;
}

std::vector<glm::vec3> stableVplDirections(int count) {
  // A spherical Fibonacci lattice (González 2010), far more even than Halton points, so that
  // neighbouring VPLs' patches tile the surface without clumps and gaps (measured on the candle
  // holder's table, 80 VPLs at 96x72: receivers' error 19.4% -> 14.2% with the patch receivers).
  std::vector<glm::vec3> out;
  out.reserve(static_cast<std::size_t>(std::max(count, 0)));
  for (int i = 0; i < count; ++i) {
    const double y = 1.0 - (2.0 * i + 1.0) / count, r = std::sqrt(std::max(0.0, 1.0 - y * y));
    const double phi = 2.39996322972865332 * i;  // the golden angle, π (3 − √5)
    out.emplace_back(glm::vec3(glm::dvec3(r * std::cos(phi), y, r * std::sin(phi))));
  }
  return out;
}

std::vector<int> vplClusters(const std::vector<glm::vec3>& directions, int clusters) {
  const std::vector<glm::vec3> centres = vplDirections(std::max(clusters, 1), 0);
  std::vector<int> out;
  out.reserve(directions.size());
  for (const glm::vec3& d : directions) {
    int best = 0;
    for (int c = 1; c < static_cast<int>(centres.size()); ++c)
      if (glm::dot(d, centres[static_cast<std::size_t>(c)]) > glm::dot(d, centres[static_cast<std::size_t>(best)])) best = c;
    out.push_back(best);
  }
  return out;
}

std::vector<VplClusterCamera> vplClusterCameras(const std::vector<VplRecord>& records, int clusters, float margin) {
  std::vector<glm::dvec3> sum(static_cast<std::size_t>(clusters), glm::dvec3(0.0));
  std::vector<int> count(static_cast<std::size_t>(clusters), 0);
  const auto clusterOf = [&](const VplRecord& r) {
    return static_cast<std::size_t>(std::clamp(static_cast<int>(r.radiance.w + 0.5f), 0, clusters - 1));
  };
  for (const VplRecord& r : records) {
    if (r.position.w <= 0.0f) continue;
    sum[clusterOf(r)] += glm::dvec3(glm::vec3(r.position));
    ++count[clusterOf(r)];
  }
  // The medoid: the cluster's VPL nearest its mean. It stands on the surface (the mean of a curved
  // patch lies inside the object, and moving it out by the patch's size can put it inside a
  // neighbouring object), so the camera is that VPL lifted by `margin` along its normal.
  std::vector<double> best(static_cast<std::size_t>(clusters), 1e300);
  std::vector<VplClusterCamera> out(static_cast<std::size_t>(clusters));
  for (const VplRecord& r : records) {
    if (r.position.w <= 0.0f) continue;
    const std::size_t c = clusterOf(r);
    const glm::dvec3 x(glm::vec3(r.position));
    const double d = glm::length(x - sum[c] / double(count[c]));
    if (d >= best[c]) continue;
    best[c] = d;
    out[c].position = glm::vec3(r.position) + margin * glm::vec3(r.normal);
    out[c].valid = true;
  }
  return out;
}

std::vector<glm::vec3> surroundedLights(const Scene& scene, const glm::vec3& boxMin, const glm::vec3& boxMax) {
  std::vector<glm::vec3> out;
  for (const Light& l : scene.lights)
    if (l.kind == LightKind::Point && glm::all(glm::greaterThanEqual(l.position, boxMin)) &&
        glm::all(glm::lessThanEqual(l.position, boxMax)))
      out.push_back(l.position);
  return out;
}

VirtualPointLights::VirtualPointLights(const gpu::ShaderLibrary& shaders)
    : cubeProgram_(shaders, layeredProgram("maps/map_gbuffer.frag")),
      compute_(shaders, {{{GL_COMPUTE_SHADER, "maps/vpl.comp"}}}),
      receivers_(shaders, {{{GL_COMPUTE_SHADER, "maps/vpl_receivers.comp"}}}),
      shadows_(shaders) {}

namespace {
bool gComputeReceivers = true;  ///< VirtualPointLights::allowComputeReceivers (tests)
}  // namespace

bool VirtualPointLights::computeReceivers() { return gComputeReceivers; }
void VirtualPointLights::allowComputeReceivers(bool allow) { gComputeReceivers = allow; }

void VirtualPointLights::lightReceivers(const CameraTarget& target, const RenderSettings& settings) {
  if (count_ == 0) return;
  constexpr GLuint kGroup = 8;  // vpl_receivers.comp's local size
  constexpr GLuint kReceiverUnit = 0, kAlbedoUnit = 1, kShadowUnit = 2;
  setReceiverUniforms(receivers_, this, kShadowUnit);
  receivers_.set("uPcfRadius", settings.pcfRadius);  // the normal offset of the VPL shadows (common/lights.glsl)
  receivers_.set("uShadowBias", settings.shadowBias);
  receivers_.set("uReceiver", static_cast<int>(kReceiverUnit));
  receivers_.set("uReceiverAlbedo", static_cast<int>(kAlbedoUnit));
  target.receiver.bind(kReceiverUnit);
  target.receiverAlbedo.bind(kAlbedoUnit);
  // The camera pass's colour writes become visible to this pass's fetches and image loads.
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
  glBindImageTexture(0, target.radiance.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
  receivers_.use();
  glDispatchCompute((static_cast<GLuint>(target.radiance.width()) + kGroup - 1) / kGroup,
                    (static_cast<GLuint>(target.radiance.height()) + kGroup - 1) / kGroup, 1);
  // Later passes sample, fetch, read as an image or copy the radiance.
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT |
                  GL_FRAMEBUFFER_BARRIER_BIT | GL_PIXEL_BUFFER_BARRIER_BIT);
  gpu::unbindComputeState(1, 3);
}

bool VirtualPointLights::applies(const Scene& scene, const RenderSettings& settings) {
  return settings.vpl.count > 0 && RadiosityMaps::applies(scene, settings) && anyOpaque(scene);
}

void VirtualPointLights::checkLimits(const Scene& scene, const RenderSettings& settings) {
  if (!applies(scene, settings)) return;
  const GLint maxCube = gpu::glLimits().maxCubeMapTextureSize, maxBlock = gpu::glLimits().maxShaderStorageBlockSize;
  if (settings.vpl.cubeSize > maxCube)
    throw std::invalid_argument("vpl.cube_size: " + std::to_string(settings.vpl.cubeSize) +
                                " exceeds this GPU's GL_MAX_CUBE_MAP_TEXTURE_SIZE of " + std::to_string(maxCube));
  // The largest block is the parts' (kVplParts records per VPL).
  const auto bytes = static_cast<long long>(settings.vpl.count) * kVplParts * static_cast<long long>(sizeof(VplRecord));
  if (settings.vpl.shadows && 6 * settings.vpl.shadowClusters > gpu::glLimits().maxArrayTextureLayers)
    throw std::invalid_argument("vpl.shadow_clusters: " + std::to_string(settings.vpl.shadowClusters) +
                                " cube maps exceed this GPU's GL_MAX_ARRAY_TEXTURE_LAYERS");
  if (settings.vpl.shadows && settings.vpl.shadowSize > maxCube)
    throw std::invalid_argument("vpl.shadow_size: " + std::to_string(settings.vpl.shadowSize) +
                                " exceeds this GPU's GL_MAX_CUBE_MAP_TEXTURE_SIZE of " + std::to_string(maxCube));
  if (bytes > maxBlock)
    throw std::invalid_argument("vpl.count: " + std::to_string(settings.vpl.count) + " VPLs need " +
                                std::to_string(bytes) + " bytes for their cells' parts, over this GPU's GL_MAX_SHADER_STORAGE_BLOCK_SIZE of " +
                                std::to_string(maxBlock));
}

VplPlacement VirtualPointLights::placement(const Scene& scene, const RenderSettings& settings,
                                           const SceneGeometry& geometry) {
  if (settings.vpl.placement != VplPlacement::Auto) return settings.vpl.placement;
  const geometry::Aabb box = translucentBox(scene, geometry);
  if (box.empty()) return VplPlacement::All;
  return surroundedLights(scene, box.min, box.max).empty() ? VplPlacement::All : VplPlacement::Backlit;
}

std::string VirtualPointLights::describe(const Scene& scene, const RenderSettings& settings) {
  const VplSettings& v = settings.vpl;
  std::string placement = v.placement == VplPlacement::All       ? "on all of the outermost surface"
                          : v.placement == VplPlacement::Backlit ? "on backlit surface only"
                                                                 : "on backlit surface when a point light is inside the "
                                                                   "translucent objects' box, else on all of it";
  (void)scene;
  return std::to_string(v.count) + " VPLs " + placement + ": outermost surface into a " +
         std::to_string(v.cubeSize) + "^2 cube from the box centre, " + (v.stable ? "fixed" : "new every frame") +
         " Halton directions, B(x_v) by Algorithm 1, A_v by " +
         (v.area == VplArea::SolidAngle ? "the cube's solid angle" : "the bounding box's area") +
         "; receivers lit with the bounded geometry term (Eqs. 15-16)";
}

void VirtualPointLights::render(const Scene& scene, const RenderSettings& settings, const SceneGeometry& geometry,
                                const RadiosityMaps& maps, int frame, bool countCoverage) {
  const VplSettings& v = settings.vpl;
  count_ = v.count;
  const geometry::Aabb box = translucentBox(scene, geometry);
  if (box.empty() || count_ <= 0) {
    count_ = 0;
    return;
  }
  centre_ = box.centre();
  const glm::vec3 size = box.size();
  boxArea_ = 2.0f * (size.x * size.y + size.y * size.z + size.z * size.x);

  // Directions: uploaded once while stable, new Halton points every frame otherwise.
  const int first = v.stable ? kStableFirst : kStableFirst + (1 + frame) * count_;
  const int clusters = std::clamp(v.shadowClusters, 1, kMaxVplShadowClusters);
  if (!directions_.id() || directions_.size() != static_cast<std::size_t>(count_) * sizeof(glm::vec4) ||
      first != directionsFirst_ || clusters != directionsClusters_) {
    const std::vector<glm::vec3> dirs = v.stable ? stableVplDirections(count_) : vplDirections(count_, first);
    const std::vector<int> cluster = vplClusters(dirs, clusters);
    std::vector<glm::vec4> d;  // w: the shadow cluster (vpl.comp copies it into the record)
    for (std::size_t i = 0; i < dirs.size(); ++i) d.emplace_back(dirs[i], static_cast<float>(cluster[i]));
    directions_ = gpu::Buffer(d.size() * sizeof(glm::vec4), d.data());
    directionsFirst_ = first;
    directionsClusters_ = clusters;
  }
  if (records_.size() != static_cast<std::size_t>(count_) * sizeof(VplRecord))
    records_ = gpu::Buffer(static_cast<std::size_t>(count_) * sizeof(VplRecord));
  if (parts_.size() != static_cast<std::size_t>(count_) * kVplParts * sizeof(VplRecord))
    parts_ = gpu::Buffer(static_cast<std::size_t>(count_) * kVplParts * sizeof(VplRecord));

  // Step 1: the outermost surface around the centre.
  const int cube = v.cubeSize;
  if (!cubePosition_.id() || cubePosition_.width() != cube) {
    cubePosition_ = gpu::Texture::createCube(kGBufferPositionFormat, cube);
    cubePosition_.setFilter(GL_NEAREST, GL_NEAREST);
    cubeNormal_ = gpu::Texture::createCube(gBufferNormalFormat(), cube);
    cubeNormal_.setFilter(GL_NEAREST, GL_NEAREST);
    cubeDepth_ = gpu::Texture::createCube(GL_DEPTH_COMPONENT32F, cube);
  }
  const float range = 0.5f * glm::length(size) * 1.01f + 1e-6f;
  const auto faces = cubeFaceViewProjections(centre_, range * 1e-4f, range);
  faceViews_.assign(sizeof(faces), faces.data());
  {
    CubePassState state;
    // Depth cleared to the near plane: any surface is farther.
    gpu::bindGBuffer(cubeTarget_, cubePosition_, cubeNormal_, cubeDepth_, 0.0f, "VPL outermost-surface cube");
    glViewport(0, 0, cube, cube);
    cubeProgram_.use();
    setSlotUniforms(cubeProgram_, maps.slotTable(), false);
    drawTranslucentLayered(cubeProgram_, geometry, maps.slots(), faceViews_, 6);
  }

  // Step 2: the VPLs.
  gpu::Program& p = compute_;
  p.use();
  maps.setAlgorithm1Uniforms(p, settings, kMapsUnit, kMapDepthUnit, false, countCoverage);
  setSlotUniforms(p, maps.slotTable(), false);  // η per slot: the pool's VPLs leave through the liquid
  std::vector<glm::vec3> from;
  if (placement(scene, settings, geometry) == VplPlacement::Backlit) from = surroundedLights(scene, box.min, box.max);
  p.set("uBacklitCount", static_cast<int>(from.size()));
  if (!from.empty()) p.set("uBacklitFrom", from.data(), static_cast<int>(from.size()));
  p.set("uVplCount", count_);
  p.set("uCentre", centre_);
  p.set("uAreaMode", v.area == VplArea::SolidAngle ? 0 : 1);
  p.set("uBoxArea", boxArea_);
  p.set("uCubePosition", static_cast<int>(kCubePositionUnit));
  p.set("uCubeNormal", static_cast<int>(kCubeNormalUnit));
  cubePosition_.bind(kCubePositionUnit);
  cubeNormal_.bind(kCubeNormalUnit);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kRecordsBinding, records_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kDirectionsBinding, directions_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPartsBinding, parts_.id());
  glDispatchCompute(static_cast<GLuint>((count_ * (1 + kVplParts) + 63) / 64), 1, 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  glUseProgram(0);

  // Step 3 (vpl.shadows): one cube shadow map per cluster, from just outside its VPLs. The cameras
  // come from the records read back (N_vpl × 48 bytes), then the shadow pass draws the scene as for
  // point lights.
  shadowed_ = v.shadows;
  clusterCentre_.assign(static_cast<std::size_t>(clusters), glm::vec3(0.0f));
  clusterRange_.assign(static_cast<std::size_t>(clusters), 0.0f);
  clusterCube_.assign(static_cast<std::size_t>(clusters), 0);
  if (!v.shadows) return;
  const float margin = 1e-2f * glm::length(size);
  const std::vector<VplClusterCamera> cameras = vplClusterCameras(read(), clusters, margin);
  Scene casters;
  std::vector<int> lightOf(static_cast<std::size_t>(clusters), -1);
  for (std::size_t c = 0; c < cameras.size(); ++c) {
    if (!cameras[c].valid) continue;
    Light l;
    l.kind = LightKind::Point;
    l.position = cameras[c].position;
    l.castsShadows = true;
    lightOf[c] = static_cast<int>(casters.lights.size());
    casters.lights.push_back(l);
    clusterCentre_[c] = cameras[c].position;
  }
  if (casters.lights.empty()) return;
  RenderSettings shadowSettings = settings;
  shadowSettings.shadows = true;
  shadowSettings.shadowMapSize = 2 * v.shadowSize;  // ShadowPass gives cube faces half the map size
  shadows_.reset(casters.lights.size());
  shadows_.renderPoint(casters, shadowSettings, geometry);
  const ShadowLayers& layers = shadows_.layers();
  for (std::size_t c = 0; c < cameras.size(); ++c)
    if (lightOf[c] >= 0) {
      const auto i = static_cast<std::size_t>(lightOf[c]);
      clusterRange_[c] = layers.pointRange[i];
      clusterCube_[c] = layers.pointCube[i];
    }
}

void VirtualPointLights::setReceiverUniforms(gpu::Program& program, const VirtualPointLights* lights,
                                             GLuint shadowUnit) {
  const int n = lights ? lights->count_ : 0;
  program.set("uVplCount", n);
  program.set("uVplCentre", n > 0 ? lights->centre_ : glm::vec3(0.0f));
  program.set("uVplShadow", static_cast<int>(shadowUnit));
  const bool shadowed = n > 0 && lights->shadowed_;
  program.set("uVplShadows", shadowed ? 1 : 0);
  if (lights) lights->shadows_.bindPoint(shadowUnit);
  if (n > 0) {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kRecordsBinding, lights->records_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPartsBinding, lights->parts_.id());
  }
  if (!shadowed) return;
  const int clusters = static_cast<int>(lights->clusterCentre_.size());
  program.set("uVplClusterCentre", lights->clusterCentre_.data(), clusters);
  glProgramUniform1fv(program.id(), program.location("uVplClusterRange"), clusters, lights->clusterRange_.data());
  glProgramUniform1iv(program.id(), program.location("uVplClusterCube"), clusters, lights->clusterCube_.data());
  program.set("uVplShadowTexelAngle", lights->shadows_.layers().pointTexelAngle);
}

std::vector<VplRecord> VirtualPointLights::read() const {
  std::vector<VplRecord> out(static_cast<std::size_t>(count_));
  if (count_ > 0) records_.download(0, out.size() * sizeof(VplRecord), out.data());
  return out;
}

std::vector<VplRecord> VirtualPointLights::readParts() const {
  std::vector<VplRecord> out(static_cast<std::size_t>(count_) * kVplParts);
  if (count_ > 0) parts_.download(0, out.size() * sizeof(VplRecord), out.data());
  return out;
}

std::size_t VirtualPointLights::bytes() const {
  return cubePosition_.bytes() + cubeNormal_.bytes() + cubeDepth_.bytes() + records_.size() + parts_.size() +
         directions_.size() +
         faceViews_.size() + (shadowed_ ? shadows_.bytes() : 0);
}

}  // namespace tallow::sss
