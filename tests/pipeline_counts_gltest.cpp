// Issue 39, point 6: the driver's pipeline statistics per pass (GL_ARB_pipeline_statistics_query),
// read with the GPU times (gpu::GpuTimer) into stats.json. Checked against counts known by
// construction: the invocations of compute dispatches of chosen sizes, nested passes' sums, one
// invocation per pixel of the still average, one geometry-shader invocation per layered triangle.
#include <gtest/gtest.h>

#include <string>

#include "gpu/gl_context.h"
#include "gpu/gl_limits.h"
#include "gpu/gpu_timer.h"
#include "gpu/program.h"
#include "gpu/shader_library.h"
#include "sss/maps/layered_program.h"
#include "support/render_support.h"
#include "support/temp_dir.h"

namespace tallow {
namespace {

const gpu::PassTiming* pass(const sss::FrameTimings& t, const std::string& name) {
  for (const gpu::PassTiming& p : t.passes)
    if (p.name == name) return &p;
  return nullptr;
}

class PipelineCounts : public ::testing::Test {
 protected:
  void SetUp() override {
    context_ = gpu::GlContext::create(gpu::ContextOptions{});
    if (!gpu::glLimits().pipelineStatistics) GTEST_SKIP() << "the driver cannot count (no GL_ARB_pipeline_statistics_query)";
  }
  std::unique_ptr<gpu::GlContext> context_;
};

// Nested passes: the outer one's counts hold the inner one's, and the work between them is the
// outer one's own; a compute dispatch of G groups of 8 invocations counts 8·G.
TEST_F(PipelineCounts, NestedPassesAddTheirComputeInvocations) {
  test::TempDir dir;
  dir.write("count.comp", "#version 450 core\nlayout(local_size_x = 8) in;\nvoid main() {}\n");
  const gpu::ShaderLibrary shaders(dir.path());
  const gpu::Program program(shaders, {{{GL_COMPUTE_SHADER, "count.comp"}}});
  gpu::GpuTimer timer;
  for (int frame = 0; frame < 2; ++frame) {  // the second frame reuses the pools
    const std::uint64_t number = timer.beginFrame();
    program.use();
    {
      gpu::GpuScope outer(timer, "outer");
      glDispatchCompute(3, 1, 1);  // 24
      {
        gpu::GpuScope inner(timer, "inner");
        glDispatchCompute(16, 1, 1);  // 128
      }
      glDispatchCompute(1, 2, 1);  // 16
    }
    glDispatchCompute(5, 1, 1);  // outside every pass: not counted
    {
      gpu::GpuScope after(timer, "after");
      glDispatchCompute(2, 1, 1);  // 16
    }
    glUseProgram(0);
    const auto counts = timer.counts(number, true);
    ASSERT_TRUE(counts.has_value());
    ASSERT_EQ(counts->size(), 3u);
    EXPECT_EQ((*counts)[0].compute, 24u + 128u + 16u);
    EXPECT_EQ((*counts)[1].compute, 128u);
    EXPECT_EQ((*counts)[2].compute, 16u);
    EXPECT_EQ((*counts)[0].fragment, 0u);
    EXPECT_EQ((*counts)[0].vertex, 0u);
  }
}

// A frame's passes in stats: the still average runs one invocation per pixel (a size of whole work
// groups), and the layered light G-buffer runs the geometry shader once per triangle and layer
// only where the vertex shader cannot choose the layer.
TEST_F(PipelineCounts, AFramesPassesCountWhatTheyDraw) {
  context_.reset();
  const std::vector<std::string> sets = {"render.width=64", "render.height=48", "field.res=32", "vpl.count=0",
                                         "sss.frames=1"};
  sss::FrameTimings counted[2];
  for (int variant = 0; variant < 2; ++variant) {
    sss::allowLayerInVertexShader(variant == 0);
    test::PresetSession s("candle", sets);
    sss::FrameTimings t = s.renderFrame(10.0);
    sss::allowLayerInVertexShader(true);
    ASSERT_TRUE(s.renderer().resolveTimings(t, true));
    counted[variant] = t;
  }
  const gpu::PassTiming* still = pass(counted[0], "camera.still");
  ASSERT_NE(still, nullptr);
  ASSERT_TRUE(still->counts.has_value());
  EXPECT_EQ(still->counts->compute, 64u * 48u);

  const gpu::PassTiming* vertexLayer = pass(counted[0], "sss.light_gbuffer");
  const gpu::PassTiming* geometryLayer = pass(counted[1], "sss.light_gbuffer");
  ASSERT_NE(vertexLayer, nullptr);
  ASSERT_NE(geometryLayer, nullptr);
  ASSERT_TRUE(vertexLayer->counts && geometryLayer->counts);
  EXPECT_EQ(vertexLayer->counts->geometry, 0u);
  EXPECT_GT(geometryLayer->counts->primitives, 1000u);  // the candle's triangles, once per cube face
  EXPECT_EQ(geometryLayer->counts->geometry, geometryLayer->counts->primitives);
  EXPECT_EQ(vertexLayer->counts->primitives, geometryLayer->counts->primitives);
}

}  // namespace
}  // namespace tallow
