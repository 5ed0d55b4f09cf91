#include "sss/peers/sslpv.h"

#include <algorithm>
#include <climits>
#include <stdexcept>

#include "gpu/gl_limits.h"

namespace tallow::sss {
namespace {

constexpr GLuint kAccumulationUnit = 0;  // + 0, 1, 2 relative to the caller's first unit
constexpr GLuint kMediumUnit = 3;
/// cos θ_c of Eq. 7's cap for sslpv.exitance = face: 2π(1 − cos θ_c) = 2π/3, one face of six.
constexpr float kFaceCapCos = 2.0f / 3.0f;

std::vector<int> translucentSlots(const Scene& scene) {
  std::vector<int> slots(scene.objects.size(), -1);
  int slot = 0;
  for (std::size_t i = 0; i < scene.objects.size(); ++i)
    if (scene.objects[i].translucent) slots[i] = slot++;
  return slots;
}

int translucentCount(const Scene& scene) {
  return static_cast<int>(std::count_if(scene.objects.begin(), scene.objects.end(),
                                        [](const SceneObject& o) { return o.translucent; }));
}

geometry::Aabb translucentBox(const Scene& scene, const SceneGeometry& geometry) {
  geometry::Aabb box;
  for (const DrawItem& item : geometry.items()) {
    if (!scene.objects[static_cast<std::size_t>(item.objectIndex)].translucent || item.worldBounds.empty()) continue;
    box.extend(item.worldBounds.min);
    box.extend(item.worldBounds.max);
  }
  return box;
}

}  // namespace

Sslpv::Sslpv(const gpu::ShaderLibrary& shaders)
    : gbuffers_(shaders), medium_(shaders), injection_(shaders), propagation_(shaders) {}

bool Sslpv::applies(const Scene& scene, const RenderSettings& settings) {
  return settings.sss.method == SssMethod::Sslpv && translucentCount(scene) > 0;
}

std::size_t Sslpv::gridBytes(int size, int objects) {
  const auto cells = static_cast<std::size_t>(size) * size * size;
  const auto samples = static_cast<std::size_t>(2 * size);
  // 3 bands × (2 propagation + 1 accumulation) grids and 3 medium grids, RGBA32F; the parity images.
  return 12 * cells * 16 + samples * samples * static_cast<std::size_t>(std::max(objects, 1)) * 3 *
                               static_cast<std::size_t>(SslpvMedium::parityWords(size)) * 4;
}

void Sslpv::checkLimits(const Scene& scene, const RenderSettings& settings) {
  if (!applies(scene, settings)) return;
  const SslpvSettings& s = settings.sslpv;
  if (s.skip >= s.steps)
    throw std::invalid_argument("sslpv.skip: " + std::to_string(s.skip) + " of " + std::to_string(s.steps) +
                                " sslpv.steps would leave the accumulation grid empty; it must be less than sslpv.steps");
  const gpu::GlLimits& limits = gpu::glLimits();
  const GLint max3d = limits.max3dTextureSize, maxTexture = limits.maxTextureSize,
              maxLayers = limits.maxArrayTextureLayers, maxCube = limits.maxCubeMapTextureSize;
  const int objects = translucentCount(scene);
  if (s.grid > max3d)
    throw std::invalid_argument("sslpv.grid: " + std::to_string(s.grid) + " exceeds this GPU's GL_MAX_3D_TEXTURE_SIZE of " +
                                std::to_string(max3d));
  if (2 * s.grid > maxTexture || objects * 3 * SslpvMedium::parityWords(s.grid) > maxLayers)
    throw std::invalid_argument("sslpv.grid: the voxelisation of " + std::to_string(objects) + " object(s) at " +
                                std::to_string(s.grid) + "³ exceeds this GPU's GL_MAX_TEXTURE_SIZE or "
                                "GL_MAX_ARRAY_TEXTURE_LAYERS");
  const std::size_t bytes = gridBytes(s.grid, objects);
  if (bytes > kSslpvMemoryBudget)
    throw std::invalid_argument("sslpv.grid: " + std::to_string(s.grid) + "³ cells need " +
                                std::to_string(bytes >> 20) + " MiB of grids, over the " +
                                std::to_string(kSslpvMemoryBudget >> 20) + " MiB SSLPV budget");
  int dir = 0, point = 0;
  for (const Light& l : scene.lights) (l.kind == LightKind::Directional ? dir : point)++;
  if (s.injectSize > maxTexture || (point > 0 && s.injectSize > maxCube))
    throw std::invalid_argument("sslpv.inject_size: " + std::to_string(s.injectSize) + " exceeds this GPU's " +
                                (s.injectSize > maxTexture ? "GL_MAX_TEXTURE_SIZE of " + std::to_string(maxTexture)
                                                           : "GL_MAX_CUBE_MAP_TEXTURE_SIZE of " + std::to_string(maxCube)));
  const long long points = static_cast<long long>(s.injectSize) * s.injectSize * (dir + 6LL * point);
  if (points > INT_MAX)
    throw std::invalid_argument("sslpv.inject_size: " + std::to_string(points) + " texels to inject exceed one draw's " +
                                std::to_string(INT_MAX));
}

std::string Sslpv::describeVoxelize(const Scene& scene, const RenderSettings& settings) {
  const int n = settings.sslpv.grid;
  return std::to_string(translucentCount(scene)) + " translucent object(s) voxelised by parity along x, y and z into a " +
         std::to_string(n) + "^3 LPV grid (2^3 sub-samples per cell) with their sigma_t, sigma'_s and g per cell";
}

std::string Sslpv::describeLightGBuffer(const Scene& scene, const RenderSettings& settings) {
  int dir = 0, point = 0;
  for (const Light& l : scene.lights) (l.kind == LightKind::Directional ? dir : point)++;
  return std::to_string(dir) + " directional (orthographic layer) and " + std::to_string(point) +
         " point (cube) light G-buffer(s) of " + std::to_string(settings.sslpv.injectSize) +
         "^2 for the injection (the paper's RSMs)";
}

std::string Sslpv::describeInject(const RenderSettings& settings) {
  return "every G-buffer texel on a translucent surface: its transmitted flux as a cosine lobe about the refracted "
         "direction (Eq. 1) on 2-band SH, added to its cell of the " +
         std::to_string(settings.sslpv.grid) + "^3 grid";
}

std::string Sslpv::describePropagate(const RenderSettings& settings) {
  const SslpvSettings& s = settings.sslpv;
  return std::to_string(s.steps) + " steps of face-flux propagation with absorption and scattering (Sec. 3.2, Eq. 3, " +
         "Sec. 4), accumulated from step " + std::to_string(s.skip + 1);
}

RenderSettings Sslpv::gbufferSettings(const RenderSettings& settings) {
  RenderSettings s = settings;
  s.sss.lightMapSize = settings.sslpv.injectSize;
  s.sss.lightMapAuto = false;
  return s;
}

void Sslpv::voxelize(const Scene& scene, const RenderSettings& settings, const SceneGeometry& geometry) {
  slots_ = translucentSlots(scene);
  grid_ = fitSslpvGrid(translucentBox(scene, geometry), settings.sslpv.grid);
  medium_.build(scene, geometry, slots_, grid_);
}

void Sslpv::renderLightGBuffers(const Scene& scene, const RenderSettings& settings, const SceneGeometry& geometry) {
  gbuffers_.renderLightGBuffers(scene, gbufferSettings(settings), geometry);
}

void Sslpv::inject(const Scene& scene, const RenderSettings& settings) {
  propagation_.resize(grid_.size);
  propagation_.clear();
  injection_.inject(scene, gbufferSettings(settings), gbuffers_, grid_, propagation_.current());
}

void Sslpv::propagate(const RenderSettings& settings) {
  propagation_.propagate(settings.sslpv.steps, settings.sslpv.skip, grid_.cellMm(), medium_);
}

void Sslpv::setLookupUniforms(gpu::Program& p, const RenderSettings& settings, GLuint firstUnit) const {
  p.set("uSslpvAccR", static_cast<int>(firstUnit + kAccumulationUnit));
  p.set("uSslpvAccG", static_cast<int>(firstUnit + kAccumulationUnit + 1));
  p.set("uSslpvAccB", static_cast<int>(firstUnit + kAccumulationUnit + 2));
  p.set("uSslpvMedium", static_cast<int>(firstUnit + kMediumUnit));
  p.set("uSslpvOrigin", grid_.origin);
  p.set("uSslpvCell", grid_.cell);
  p.set("uSslpvCapCos", settings.sslpv.exitance == SslpvExitance::Face ? kFaceCapCos : 0.0f);
  for (GLuint c = 0; c < 3; ++c) propagation_.accumulation()[c].bind(firstUnit + kAccumulationUnit + c);
  medium_.extinction().bind(firstUnit + kMediumUnit);
}

void Sslpv::setLookupOff(gpu::Program& p, GLuint firstUnit) {
  p.set("uSslpvAccR", static_cast<int>(firstUnit + kAccumulationUnit));
  p.set("uSslpvAccG", static_cast<int>(firstUnit + kAccumulationUnit + 1));
  p.set("uSslpvAccB", static_cast<int>(firstUnit + kAccumulationUnit + 2));
  p.set("uSslpvMedium", static_cast<int>(firstUnit + kMediumUnit));
}

std::size_t Sslpv::bytes() const { return gbuffers_.bytes() + medium_.bytes() + propagation_.bytes(); }

}  // namespace tallow::sss
