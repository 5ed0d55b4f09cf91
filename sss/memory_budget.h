#pragma once
// The GPU memory a frame allocates, as pure functions of the scene and the settings, checked
// against what the GPU offers (gpu/gpu_memory.h) before anything is allocated. Each figure is the
// bytes() of the objects it stands for once they exist (tests/memory_budget_gltest.cpp allocates
// them and compares), so that the check counts what the renderer really takes: the radiosity maps
// with their mip chain, depth and compute G-buffer, the light G-buffers, the VPLs with their
// cluster shadow maps, the camera's render targets, the shadow maps, the dual-contouring buffers
// and the peer methods' screen buffers and grids.
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "sss/render_settings.h"
#include "sss/scene.h"

namespace tallow::sss {

/// One thing a frame allocates.
struct MemoryItem {
  std::string name;      ///< e.g. "radiosity maps"
  std::string sizedBy;   ///< the parameters that size it, with their values: "sss.maps=8 x sss.map_size=4096^2"
  std::size_t bytes = 0;
};

struct FrameMemory {
  std::vector<MemoryItem> items;  ///< in the order of the frame's passes; only what the frame needs
  std::size_t total() const;
  /// Appends an item (nothing when bytes is 0).
  void add(std::string name, std::string sizedBy, std::size_t bytes);
};

/// The sizes the renderer chose (> 0; 0: not chosen yet): sss.light_map_size and sss.map_size.
struct BudgetSizes {
  int lightMapSize = 0, mapSize = 0;
};
/// The scene's translucent objects.
int translucentObjectCount(const Scene& scene);
/// "key=value²".
std::string squareText(const char* key, int value);
/// The size to count for `key`: the renderer's choice (> 0), else the setting, "auto" not yet
/// chosen as kAutoBudgetSize; with the text naming it.
std::pair<int, std::string> budgetSize(const char* key, int chosen, int setting);

/// The camera pass's targets: radiance (RGBA32F), coverage (RGBA8) and depth (32F).
std::size_t renderTargetBytes(int width, int height);
/// The shadow maps of the lights that cast shadows (ShadowPass::bytes()): a render.shadow_map_size²
/// layer per directional light, a cube of half that size per point light.
std::size_t shadowMapBytes(const Scene& scene, const RenderSettings& settings);
/// Light G-buffers (position, normal: RGBA32F; depth: 32F) of `directional` orthographic layers
/// and `point` cubes, `size`² texels per layer or face.
std::size_t lightGBufferBytes(int directional, int point, int size);
/// K scattered radiosity maps of size²: RGBA32F with the full mip chain, depth, with the compute
/// gather (sss.gather) or the history (sss.history > 0) the maps' own G-buffer (position, normal),
/// and with the history the last frame's G-buffer as well.
std::size_t radiosityMapBytes(int k, int size, bool computeGather, bool history);
/// The virtual point lights without their shadow maps: the outermost-surface cube (position,
/// normal, depth), the records, the directions and the cube's face views.
std::size_t vplBytes(const VplSettings& vpl);
/// The VPL clusters' cube shadow maps (vpl.shadows): one vpl.shadow_size² cube per cluster.
std::size_t vplShadowBytes(const VplSettings& vpl);
/// One field object's dual contouring at n³ samples (GpuDualContouring::bufferBytes()): the field
/// and index textures, the vertex and mesh transform-feedback buffers at their capacities, the
/// block list, counters and patch table.
std::size_t dualContouringBytes(int samplesPerAxis);
/// The image-space method's screen buffers and sample pattern (ImageSpaceSss::bytes()).
std::size_t imageSpaceBytes(int width, int height, int translucentObjects, const ImageSpaceSettings& settings);

/// Everything the frame of `scene` with `settings` allocates on the GPU. `lightMapSize` and
/// `mapSize` > 0 stand for the sizes the renderer chose (sss.light_map_auto, or "auto" for
/// sss.light_map_size and sss.map_size: they depend on the geometry and the camera, known only once
/// the frame has begun); an "auto" not yet chosen counts as kAutoBudgetSize.
FrameMemory frameMemory(const Scene& scene, const RenderSettings& settings, int lightMapSize = 0, int mapSize = 0);
/// What frameMemory counts for an "auto" size that is not yet chosen (the paper's 512).
constexpr int kAutoBudgetSize = 512;

/// Throws std::invalid_argument with one line when frameMemory() exceeds the memory the current
/// GL context's GPU offers (gpu::gpuMemory()), naming the total, the GPU's figure and where it
/// comes from, and the largest items with the parameters that size them.
void checkMemoryBudget(const Scene& scene, const RenderSettings& settings, int lightMapSize = 0, int mapSize = 0);

}  // namespace tallow::sss
