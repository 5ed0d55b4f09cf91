#include "sss/memory_budget.h"

#include <algorithm>
#include <array>
#include <bit>
#include <glm/glm.hpp>
#include <stdexcept>

#include "geometry/gpu_dual_contouring.h"
#include "gpu/gl_objects.h"
#include "gpu/gpu_memory.h"
#include "sss/bloom.h"
#include "sss/local_exposure.h"
#include "sss/field_objects.h"
#include "sss/maps/gbuffer_formats.h"
#include "sss/maps/radiosity_maps.h"
#include "sss/maps/virtual_point_lights.h"
#include "sss/peers/image_space.h"
#include "sss/peers/sslpv.h"
#include "sss/frame_plan.h"
#include "sss/shadow_pass.h"
#include "sss/translucency_method.h"
#include "sss/still_average.h"

namespace tallow::sss {
namespace {

using gpu::Texture;

/// The largest items named in the refusal: enough to see what to lower, short enough for one line.
constexpr std::size_t kItemsNamed = 3;
/// GpuDualContouring's transform-feedback records (gpu_dual_contouring.cpp): a vertex is position,
/// normal, cell and bits; a mesh vertex is position, normal and vertex index, each 4 bytes.
constexpr std::size_t kDcVertexBytes = 8 * sizeof(float);
constexpr std::size_t kDcMeshVertexBytes = 7 * sizeof(float);
/// Its patch table (one word per sign configuration of a cell's 8 corners), draw command and
/// vertex counter (four words each).
constexpr std::size_t kDcPatchTableBytes = 256 * sizeof(std::uint32_t);
constexpr std::size_t kDcCommandBytes = 4 * sizeof(std::uint32_t);
/// The compute path's mesh counts (8 words), their read-back copy (4 words) and its 8 draw commands
/// (4 words each), allocated whichever path runs.
constexpr std::size_t kDcComputeCountBytes = (8 + 4 + 8 * 4) * sizeof(std::uint32_t);

std::size_t layers2D(GLenum format, int size, int layers, int levels = 1) {
  return Texture::bytesFor(GL_TEXTURE_2D_ARRAY, format, size, size, layers, levels);
}
std::size_t cubes(GLenum format, int size, int count) {
  return Texture::bytesFor(GL_TEXTURE_CUBE_MAP_ARRAY, format, size, size, 6 * count, 1);
}
std::size_t screen(GLenum format, int width, int height) {
  return Texture::bytesFor(GL_TEXTURE_2D, format, width, height, 1, 1);
}



}  // namespace

std::size_t FrameMemory::total() const {
  std::size_t n = 0;
  for (const MemoryItem& i : items) n += i.bytes;
  return n;
}

std::size_t renderTargetBytes(int width, int height) {
  // sss::CameraTarget: radiance, coverage, coverage bins, the translucent part, depth, the opaque
  // receivers' point and normal, their albedo.
  return 2 * screen(GL_RGBA32F, width, height) + screen(GL_RGBA8, width, height) + screen(GL_RG8UI, width, height) +
         screen(GL_DEPTH_COMPONENT32F, width, height) + screen(GL_RGBA32UI, width, height) +
         screen(GL_RGBA16F, width, height);
}

std::size_t shadowMapBytes(const Scene& scene, const RenderSettings& settings) {
  if (!settings.shadows) return 0;
  int directional = 0, point = 0;
  for (const Light& l : scene.lights)
    if (l.castsShadows) (l.kind == LightKind::Directional ? directional : point)++;
  std::size_t bytes = 0;
  if (directional > 0) bytes += layers2D(GL_DEPTH_COMPONENT32F, settings.shadowMapSize, directional);
  // ShadowPass::renderPoint: cube faces of half the map size, at least 16 texels.
  if (point > 0) bytes += cubes(GL_DEPTH_COMPONENT32F, std::max(16, settings.shadowMapSize / 2), point);
  return bytes;
}

std::size_t lightGBufferBytes(int directional, int point, int size) {
  std::size_t bytes = 0;
  if (directional > 0)
    bytes += layers2D(kGBufferPositionFormat, size, directional) + layers2D(gBufferNormalFormat(), size, directional) +
             layers2D(GL_DEPTH_COMPONENT32F, size, directional);
  if (point > 0)
    bytes += cubes(kGBufferPositionFormat, size, point) + cubes(gBufferNormalFormat(), size, point) +
             cubes(GL_DEPTH_COMPONENT32F, size, point);
  return bytes;
}

std::size_t radiosityMapBytes(int k, int size, bool computeGather, bool history) {
  if (k <= 0) return 0;
  // The full mip chain: floor(log2 size) + 1 levels (radiosity_maps.cpp, mipLevels).
  const int levels = static_cast<int>(std::bit_width(static_cast<unsigned>(size)));
  std::size_t bytes = layers2D(GL_RGBA32F, size, k, levels) + layers2D(GL_DEPTH_COMPONENT32F, size, k);
  // The maps' G-buffer (position, normal): the compute gather's input and the history's; the
  // history keeps the last frame's as well,
  const std::size_t gbuffer = layers2D(kGBufferPositionFormat, size, k) + layers2D(kMapGBufferNormalFormat, size, k);
  if (computeGather || history) bytes += gbuffer;
  // and, on a reuse, the kept history and this frame's mean beside it, both mipmapped (the latter
  // also holds what a still after motion fades out), and the list of texels the history visits.
  if (history) bytes += gbuffer + 2 * layers2D(GL_RGBA32F, size, k, levels) + coveredTexelBytes(size, k);
  return bytes;
}

std::size_t vplBytes(const VplSettings& vpl) {
  if (vpl.count <= 0) return 0;
  const auto cube = [&](GLenum format) {
    return Texture::bytesFor(GL_TEXTURE_CUBE_MAP, format, vpl.cubeSize, vpl.cubeSize, 6, 1);
  };
  const auto count = static_cast<std::size_t>(vpl.count);
  return cube(kGBufferPositionFormat) + cube(gBufferNormalFormat()) + cube(GL_DEPTH_COMPONENT32F) + (1 + kVplParts) * count * sizeof(VplRecord) + count * sizeof(glm::vec4) +
         sizeof(std::array<glm::mat4, 6>);
}

std::size_t vplShadowBytes(const VplSettings& vpl) {
  if (vpl.count <= 0 || !vpl.shadows) return 0;
  // VirtualPointLights::render hands ShadowPass twice vpl.shadow_size, whose cube faces are half that.
  const int clusters = std::clamp(vpl.shadowClusters, 1, kMaxVplShadowClusters);
  return cubes(GL_DEPTH_COMPONENT32F, std::max(16, vpl.shadowSize), clusters);
}

std::size_t dualContouringBytes(int samplesPerAxis) {
  using geometry::GpuDualContouring;
  if (samplesPerAxis < 2) return 0;
  const auto n = static_cast<std::size_t>(samplesPerAxis);
  const std::size_t cells = n - 1;
  const std::size_t blocks = (cells + GpuDualContouring::kBlockCells - 1) / GpuDualContouring::kBlockCells;
  const std::size_t vertices = std::min(GpuDualContouring::kMaxPatchesPerCell * cells * cells * cells,
                                        GpuDualContouring::kVerticesPerFaceCell * cells * cells);
  const std::size_t triangles = GpuDualContouring::kTrianglesPerVertex * vertices;
  return blocks * blocks * blocks * sizeof(std::uint32_t) + kDcPatchTableBytes + 2 * kDcCommandBytes + kDcComputeCountBytes +
         vertices * kDcVertexBytes + triangles * 3 * kDcMeshVertexBytes +
         Texture::bytesFor(GL_TEXTURE_3D, GL_R32F, samplesPerAxis, samplesPerAxis, samplesPerAxis, 1) +
         Texture::bytesFor(GL_TEXTURE_3D, GL_R32I, samplesPerAxis - 1, samplesPerAxis - 1, samplesPerAxis - 1, 1);
}

std::size_t imageSpaceBytes(int width, int height, int translucentObjects, const ImageSpaceSettings& s) {
  // The camera's irradiance G-buffer, then ImageSpaceSss::ensureTargets' two sums and two coverages
  // in RGBA32F; then the sample pattern of every translucent slot.
  const std::size_t targets = CameraIrradianceGBuffer::bytesFor(width, height) + 4 * screen(GL_RGBA32F, width, height);
  const std::size_t pattern = static_cast<std::size_t>(std::max(translucentObjects, 1)) *
                              static_cast<std::size_t>(s.tile * s.tile) * static_cast<std::size_t>(s.samples) *
                              sizeof(ImageSpacePatternRecord);
  return targets + pattern;
}

void FrameMemory::add(std::string name, std::string sizedBy, std::size_t bytes) {
  if (bytes > 0) items.push_back({std::move(name), std::move(sizedBy), bytes});
}

int translucentObjectCount(const Scene& scene) {
  return static_cast<int>(std::count_if(scene.objects.begin(), scene.objects.end(),
                                        [](const SceneObject& o) { return o.translucent; }));
}

std::string squareText(const char* key, int value) { return std::string(key) + "=" + std::to_string(value) + "²"; }

std::pair<int, std::string> budgetSize(const char* key, int chosen, int setting) {
  const int size = chosen > 0 ? chosen : setting == kAuto ? kAutoBudgetSize : setting;
  const std::string text = chosen > 0 || setting == kAuto
                               ? "the chosen " + std::string(key) + " " + std::to_string(size) + "²"
                               : squareText(key, size);
  return {size, text};
}

FrameMemory frameMemory(const Scene& scene, const RenderSettings& settings, int lightMapSize, int mapSize) {
  FrameMemory m;
  int fields = 0;
  for (const SceneObject& o : scene.objects) fields += o.shape == ShapeKind::Field ? 1 : 0;
  m.add("dual contouring", std::to_string(fields) + " field object(s) at field.res=" + std::to_string(settings.fieldRes) + "³",
      static_cast<std::size_t>(fields) * dualContouringBytes(settings.fieldRes));
  m.add("shadow maps", "render.shadow_map_size=" + std::to_string(settings.shadowMapSize),
      shadowMapBytes(scene, settings));
  // The frame's translucency method's own (its passes' modules): TranslucencyMethod::addMemory.
  for (const auto& method : makeTranslucencyMethods())
    if (method->id() == settings.sss.method) method->addMemory(scene, settings, BudgetSizes{lightMapSize, mapSize}, m);
  m.add("render targets", "render.width × render.height=" + std::to_string(settings.width) + "x" +
                            std::to_string(settings.height),
      renderTargetBytes(settings.width, settings.height));
  if (settings.bloom > 0.0f)  // the bright part's mip chain and the picture shown
    m.add("bloom", "render.bloom>0", Bloom::bytesFor(settings.width, settings.height));
  if (settings.localExposure > 0.0f)  // the bilateral grids and the picture shown
    m.add("local exposure", "render.local_exposure>0", LocalExposure::bytesFor(settings.width, settings.height));
  if (settings.aaSamples > 1)  // sss/still_average.h: the still's three means
    m.add("still average", "render.aa=" + std::to_string(settings.aaSamples),
        StillAverage::bytesFor(settings.width, settings.height));
  return m;
}

void checkMemoryBudget(const Scene& scene, const RenderSettings& settings, int lightMapSize, int mapSize) {
  const FrameMemory m = frameMemory(scene, settings, lightMapSize, mapSize);
  const std::size_t need = m.total();
  const gpu::GpuMemory gpuMemory = gpu::gpuMemory();
  if (need <= gpuMemory.bytes) return;
  std::vector<MemoryItem> items = m.items;
  std::stable_sort(items.begin(), items.end(), [](const MemoryItem& a, const MemoryItem& b) { return a.bytes > b.bytes; });
  std::string line = "GPU memory: the frame needs " + gpu::formatBytes(need) + ", over the " +
                     gpu::formatBytes(gpuMemory.bytes) + " this GPU offers (" + gpuMemory.source + "): ";
  for (std::size_t i = 0; i < items.size() && i < kItemsNamed; ++i) {
    if (i > 0) line += ", ";
    line += items[i].name + " " + gpu::formatBytes(items[i].bytes) + " (" + items[i].sizedBy + ")";
  }
  if (items.size() > kItemsNamed) line += ", …";
  throw std::invalid_argument(line);
}

}  // namespace tallow::sss
