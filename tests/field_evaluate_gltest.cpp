// field.evaluate (issue 16, point 7): `cpu` keeps the path before the fields moved to the GPU — every
// lattice sampled on the CPU and uploaded, normals from the lattice — so that the benchmark can
// measure before and after in one run; `gpu` (the default) fills the lattice by a compute shader.
// The key is an input of field.sample: switching it re-runs the pass at the same t.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "geometry/gpu_dual_contouring.h"
#include "support/render_support.h"

namespace tallow {
namespace {

using geometry::GpuDualContouring;
using geometry::NormalSource;

const GpuDualContouring& fieldExtractor(test::PresetSession& s) {
  const auto& items = s.renderer().geometry().items();
  const auto item = std::find_if(items.begin(), items.end(), [](const sss::DrawItem& i) { return i.field != nullptr; });
  EXPECT_NE(item, items.end());
  return *item->field;
}

bool ran(const sss::FrameTimings& t, const std::string& pass) {
  return std::any_of(t.passes.begin(), t.passes.end(), [&](const gpu::PassTiming& p) { return p.name == pass; });
}

struct Case {
  const char* preset;
  NormalSource analytic;  ///< the normals of the GPU path
  double t1, t2;
};

class FieldEvaluate : public ::testing::TestWithParam<Case> {};

TEST_P(FieldEvaluate, CpuUploadsEveryFrameGpuNeverAndSwitchingResamples) {
  const Case c = GetParam();
  test::PresetSession s(c.preset, {"render.width=48", "render.height=32", "field.res=32", "sss.maps=2",
                                   "sss.samples=1", "sss.map_size=32", "sss.light_map_size=32", "vpl.count=4",
                                   "field.evaluate=cpu"});
  ASSERT_FALSE(s.settings().fieldOnGpu);
  sss::FrameTimings t;
  s.render(c.t1, &t);
  ASSERT_TRUE(ran(t, "field.sample"));
  EXPECT_EQ(fieldExtractor(s).uploadCount(), 1u);
  EXPECT_EQ(fieldExtractor(s).gpuFillCount(), 0u);
  EXPECT_EQ(fieldExtractor(s).normalSource(), NormalSource::LatticeGradient) << "the CPU path has no analytic normals";
  s.render(c.t2, &t);
  ASSERT_TRUE(ran(t, "field.sample"));
  EXPECT_EQ(fieldExtractor(s).uploadCount(), 2u) << "each new t is sampled and uploaded";
  const std::size_t cpuTriangles = fieldExtractor(s).triangleCount();

  // Same t, field.evaluate=gpu: field.sample reads the key, so it runs again, now on the GPU.
  s.settings().fieldOnGpu = true;
  s.render(c.t2, &t);
  ASSERT_TRUE(ran(t, "field.sample")) << "switching field.evaluate must re-sample the field";
  ASSERT_TRUE(ran(t, "field.extract"));
  EXPECT_EQ(fieldExtractor(s).uploadCount(), 0u) << "the GPU path uploads no lattice";
  EXPECT_EQ(fieldExtractor(s).gpuFillCount(), 1u);
  EXPECT_EQ(fieldExtractor(s).normalSource(), c.analytic);
  // The same surface either way (tests/*_gpu_gltest.cpp bound the difference tightly): a sign flip
  // of a sample within float error of 0 changes at most 24 triangles, and there are few such samples.
  const std::size_t gpuTriangles = fieldExtractor(s).triangleCount();
  ASSERT_GT(cpuTriangles, 500u);
  EXPECT_LE(std::max(cpuTriangles, gpuTriangles) - std::min(cpuTriangles, gpuTriangles), cpuTriangles / 50)
      << "CPU " << cpuTriangles << ", GPU " << gpuTriangles;

  // Nothing changed: the mesh is drawn again, not re-sampled.
  s.render(c.t2, &t);
  EXPECT_FALSE(ran(t, "field.sample"));
  EXPECT_EQ(fieldExtractor(s).gpuFillCount(), 1u);
}

INSTANTIATE_TEST_SUITE_P(Fields, FieldEvaluate,
                         ::testing::Values(Case{"candle", NormalSource::CandleGradient, 5.0, 12.0},
                                           Case{"blob", NormalSource::BlobGradient, 0.5, 1.25}),
                         [](const auto& info) { return std::string(info.param.preset); });

}  // namespace
}  // namespace tallow
