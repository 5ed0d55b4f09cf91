// Issue 39, point 3: the layered passes (light G-buffers, map depth and shading, the VPL cube,
// SSLPV's voxelisation) choose their layer in the vertex shader where the driver offers
// GL_ARB_shader_viewport_layer_array, with the pass-through geometry shader as the fallback. Both
// variants must draw the same pictures.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "gpu/gl_limits.h"
#include "sss/maps/layered_program.h"
#include "support/render_support.h"

namespace tallow {
namespace {

/// The preset rendered with the layer written by the vertex shader or by layered.geom.
gpu::Image render(const std::string& preset, const std::vector<std::string>& sets, bool layerInVertex) {
  sss::allowLayerInVertexShader(layerInVertex);
  test::PresetSession s(preset, sets);
  EXPECT_EQ(sss::layerInVertexShader(), layerInVertex);
  gpu::Image image = s.render(s.scene().startS);
  sss::allowLayerInVertexShader(true);
  return image;
}

void expectSamePictures(const std::string& preset, const std::vector<std::string>& sets) {
  const gpu::Image vertex = render(preset, sets, true);
  const gpu::Image geometry = render(preset, sets, false);
  ASSERT_EQ(vertex.pixels.size(), geometry.pixels.size());
  double lit = 0.0;
  for (std::size_t i = 0; i < vertex.pixels.size(); ++i) {
    const glm::vec4 a = vertex.pixels[i], b = geometry.pixels[i];
    lit += a.r + a.g + a.b;
    ASSERT_TRUE(a == b) << preset << ": pixel " << i << " differs: " << a.r << " " << a.g << " " << a.b << " vs "
                        << b.r << " " << b.g << " " << b.b;
  }
  EXPECT_GT(lit, 0.0) << preset << ": a black picture proves nothing";
}

class LayeredProgram : public ::testing::Test {
 protected:
  void SetUp() override {
    test::PresetSession probe("candle", {"render.width=8", "render.height=8"});
    if (!gpu::glLimits().layerInVertexShader)
      GTEST_SKIP() << "this driver lacks GL_ARB_shader_viewport_layer_array: only the fallback runs";
  }
};

// The candle: the point light's G-buffer cube, the maps' depth pre-pass and shading, the VPL cube.
TEST_F(LayeredProgram, TheVertexShadersLayerDrawsTheCandleAsTheGeometryShaderDid) {
  expectSamePictures("candle", {"render.width=96", "render.height=54", "render.aa=1", "sss.frames=1",
                                "flame.flicker=0", "field.res=48", "vpl.count=16"});
}

// A directional light's G-buffer layers and SSLPV's three voxelisation views.
TEST_F(LayeredProgram, TheVertexShadersLayerDrawsSslpvAndTheDirectionalMapsAsBefore) {
  expectSamePictures("bunny", {"render.width=64", "render.height=48", "sss.frames=1"});
  expectSamePictures("bunny", {"render.width=64", "render.height=48", "method=sslpv"});
}

}  // namespace
}  // namespace tallow
