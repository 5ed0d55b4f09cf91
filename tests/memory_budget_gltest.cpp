// The memory budget (sss/memory_budget.h) against what the renderer really allocates: each scene is
// rendered, and the budget's figures, pure functions of scene and settings, must equal the bytes()
// of the objects that exist afterwards — so the check made before allocation counts what the
// allocation takes. Also: GL out-of-memory reported as such, and the budget refusing in-process.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>
#include <vector>

#include "gpu/gl_context.h"
#include "gpu/gl_objects.h"
#include "gpu/gpu_memory.h"
#include "sss/maps/radiosity_maps.h"
#include "sss/maps/virtual_point_lights.h"
#include "sss/memory_budget.h"
#include "sss/peers/burley.h"
#include "sss/peers/image_space.h"
#include "support/error_of.h"
#include "support/render_support.h"

namespace tallow {
namespace {

struct BudgetCase {
  std::string preset;
  std::vector<std::string> sets;
  double timeS = 0.0;
};

/// Small settings, so that every case renders in a few seconds on llvmpipe.
std::vector<std::string> small(std::vector<std::string> more) {
  std::vector<std::string> sets = {"render.width=48", "render.height=32", "sss.maps=3", "sss.samples=1",
                                   "sss.map_size=64", "sss.light_map_size=32", "render.shadow_map_size=64"};
  sets.insert(sets.end(), more.begin(), more.end());
  return sets;
}

class MemoryBudget : public ::testing::TestWithParam<BudgetCase> {};

TEST_P(MemoryBudget, FiguresEqualTheBytesOfTheAllocatedObjects) {
  const BudgetCase& c = GetParam();
  test::PresetSession session(c.preset, small(c.sets));
  session.render(c.timeS);
  const sss::Renderer& renderer = session.renderer();
  const sss::Scene& scene = session.scene();
  const sss::RenderSettings& settings = session.settings();
  const sss::RadiosityMaps* maps = renderer.module<sss::RadiosityMaps>();
  const int lightMapSize = maps ? maps->lightMapSize() : 0;
  const int mapSize = maps ? maps->mapSize() : 0;  // what sss.map_size=auto chose, or the setting
  const sss::FrameMemory budget = sss::frameMemory(scene, settings, lightMapSize, mapSize);

  // Everything but the static meshes, whose size comes from their files rather than the settings.
  EXPECT_EQ(budget.total(), renderer.gpuBytes() - renderer.geometry().bytes());
  int dir = 0, point = 0;
  for (const sss::Light& l : scene.lights) (l.kind == sss::LightKind::Directional ? dir : point)++;
  if (maps && sss::RadiosityMaps::needsLightGBuffers(scene, settings)) {
    const int k = sss::RadiosityMaps::applies(scene, settings) ? sss::mapCount(scene, settings) : 0;
    EXPECT_EQ(maps->bytes(), sss::lightGBufferBytes(dir, point, lightMapSize) +
                                 sss::radiosityMapBytes(k, mapSize, settings.sss.computeGather,
                                                         settings.sss.history > 0));
  }
  if (const sss::VirtualPointLights* vpls = renderer.module<sss::VirtualPointLights>()) {
    EXPECT_EQ(vpls->bytes(), sss::vplBytes(settings.vpl) + sss::vplShadowBytes(settings.vpl));
  }
  if (const sss::ImageSpaceSss* is = renderer.module<sss::ImageSpaceSss>()) {
    int translucent = 0;
    for (const sss::SceneObject& o : scene.objects) translucent += o.translucent ? 1 : 0;
    EXPECT_EQ(is->bytes(), sss::imageSpaceBytes(settings.width, settings.height, translucent, settings.imageSpace));
  }
  if (const sss::BurleySss* b = renderer.module<sss::BurleySss>()) {
    EXPECT_EQ(b->bytes(), sss::BurleySss::bytesFor(settings.width, settings.height, settings.burley.kernel));
  }
}

INSTANTIATE_TEST_SUITE_P(
    Scenes, MemoryBudget,
    ::testing::Values(
        // A field object (dual contouring), a point light in the wax (cube G-buffer), VPLs with
        // their cluster shadow maps, the compute gather's map G-buffer.
        BudgetCase{"candle", {"field.res=32", "vpl.count=16", "vpl.cube_size=16", "vpl.shadows=true",
                              "vpl.shadow_clusters=2", "vpl.shadow_size=16"}, 12.0},
        // A directional light with its shadow map, the fragment gather (no map G-buffer).
        BudgetCase{"bunny", {"sss.gather=fragment"}},
        // sss.light_map_auto raises the light G-buffers above sss.light_map_size from the geometry.
        BudgetCase{"bunny", {"sss.light_map_auto=true"}},
        // auto sizes, chosen from the geometry and the camera once the frame has begun.
        BudgetCase{"bunny", {"sss.map_size=auto", "sss.light_map_size=auto"}},
        BudgetCase{"bunny", {"method=no-cache"}},
        BudgetCase{"bunny", {"method=image-space", "image_space.samples=4"}},
        BudgetCase{"bunny", {"method=burley"}},
        BudgetCase{"bunny", {"method=burley", "burley.kernel=separable"}},
        BudgetCase{"slab", {"method=sslpv", "sslpv.grid=8", "sslpv.inject_size=16"}}),
    [](const ::testing::TestParamInfo<BudgetCase>& info) { return std::to_string(info.index) + "_" + info.param.preset; });

TEST(MemoryBudgetLimit, TheRendererRefusesAFrameBeyondTheGpusMemory) {
  // TALLOW_GPU_MEMORY_MB stands for a driver that reports 1 MiB: the bunny's maps of 512² do not fit.
  ::setenv("TALLOW_GPU_MEMORY_MB", "1", 1);
  const std::string error =
      test::errorOf<std::invalid_argument>([] { test::PresetSession("bunny", small({"sss.map_size=512"})); });
  ::unsetenv("TALLOW_GPU_MEMORY_MB");
  EXPECT_EQ(error.rfind("GPU memory: the frame needs ", 0), 0u) << error;
  EXPECT_NE(error.find("over the 1.0 MiB this GPU offers (TALLOW_GPU_MEMORY_MB)"), std::string::npos) << error;
  EXPECT_NE(error.find("radiosity maps"), std::string::npos) << error;
  EXPECT_EQ(error.find('\n'), std::string::npos) << error;
}

TEST(MemoryBudgetLimit, TheGpuMemoryComesFromTheDriverOrTheDocumentedDefault) {
  const auto context = gpu::GlContext::create(gpu::ContextOptions{});
  const gpu::GpuMemory memory = gpu::gpuMemory();
  EXPECT_GT(memory.bytes, 0u);
  if (GLAD_GL_NVX_gpu_memory_info) {
    EXPECT_EQ(memory.source, "GL_NVX_gpu_memory_info");
  } else if (!GLAD_GL_ATI_meminfo) {
    EXPECT_EQ(memory.bytes, gpu::kDefaultGpuMemoryBytes);
  }
  ::setenv("TALLOW_GPU_MEMORY_MB", "12x", 1);
  EXPECT_EQ(test::errorOf<std::invalid_argument>([] { gpu::gpuMemory(); }),
            "TALLOW_GPU_MEMORY_MB: expected a positive number of MiB, got \"12x\"");
  ::unsetenv("TALLOW_GPU_MEMORY_MB");
}

TEST(MemoryBudgetLimit, AnAllocationTheDriverCannotHoldIsReportedAsOutOfMemory) {
#if defined(__SANITIZE_ADDRESS__)
  // llvmpipe mallocs the storage, and ASan aborts on a request above its 1 TiB maximum instead of
  // returning the null the driver would answer with GL_OUT_OF_MEMORY.
  GTEST_SKIP() << "AddressSanitizer aborts on the driver's 8 TiB malloc";
#endif
  const auto context = gpu::GlContext::create(gpu::ContextOptions{});
  // 2048 layers of 16384² RGBA32F: 8 TiB, within every size limit, beyond any GPU's memory.
  const std::string texture = test::errorOf<gpu::GpuOutOfMemory>(
      [] { gpu::Texture::create2DArray(GL_RGBA32F, 16384, 16384, 2048); });
  EXPECT_EQ(texture, "GPU out of memory allocating a 16384x16384x2048 GL_RGBA32F 2D array texture (8192.0 GiB)");
  const std::string buffer = test::errorOf<gpu::GpuOutOfMemory>([] { gpu::Buffer(std::size_t{1} << 44); });
  EXPECT_EQ(buffer, "GPU out of memory allocating a buffer (16384.0 GiB)");
  // Allocations after a failure work as before: the failure left no error behind.
  const gpu::Texture fine = gpu::Texture::create2D(GL_RGBA8, 4, 4);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

}  // namespace
}  // namespace tallow
