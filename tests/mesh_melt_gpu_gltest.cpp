// Melting mesh fields on the GPU (issue 16, points 2 and 3): the static NanoVDB grids built once by
// OpenVDB and uploaded once, the melt at t evaluated per lattice point by shaders/fields/melt.glsl,
// the lines MeshLevelSetField::melted(t) evaluates in double. (a) The GPU's lattice against the
// CPU's field at the same points within a derived float bound; (b) the NanoVDB read (PNanoVDB as C)
// against OpenVDB's own trilinear sampler of the same grid; (c) the renderer's melting mesh, filled
// on the GPU, against the CPU-sampled path; (d) the grids are uploaded once, nothing per frame.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "geometry/gpu_dual_contouring.h"
#include "geometry/gpu_melt_field.h"
#include "geometry/grid_sampler.h"
#include "geometry/mesh_level_set_field.h"
#include "geometry/mesh_melt.h"
#include "gpu/gl_context.h"
#include "gpu/shader_library.h"
#include "sss/field_objects.h"
#include "sss/field_source.h"
#include "sss/renderer.h"
#include "support/field_compare.h"
#include "support/mesh_checks.h"
#include "support/render_support.h"
#include "support/temp_dir.h"

namespace tallow {
namespace {

using geometry::GpuDualContouring;
using geometry::GpuMeltField;
using geometry::MeltAt;
using geometry::MeltGrids;
using geometry::MeltState;
using geometry::SampledLattice;

constexpr double kUnitRoundoff = 0x1p-24;  ///< u of IEEE float: a correctly rounded operation is within u relative
constexpr double kMeltS = 10.0;            ///< the test presets' melt_s

/// Times that cover the melt: unmelted, half way (between two smoothing levels, with a puddle),
/// fully melted, and beyond (clamped at f = 1).
constexpr double kTimes[] = {0.0, 0.5 * kMeltS, kMeltS, 3.0 * kMeltS};

/// The bunny as a melting mesh field object, 0.1 m, as a preset's {"field": {"type": "mesh", …}}.
sss::SceneObject meltingBunny() {
  sss::SceneObject o;
  o.name = "bunny";
  o.shape = sss::ShapeKind::Field;
  o.field.kind = sss::FieldKind::Mesh;
  o.field.meshPath = std::filesystem::path(TALLOW_TEST_DATA_DIR) / "bunny.ply";
  o.field.meltDurationS = kMeltS;
  o.transform.scale = 0.1f;
  return o;
}

/// First-order bound on |GPU float − CPU double| of shaders/fields/melt.glsl at lattice sample s,
/// operation by operation (u: float's unit roundoff). The sample's position fl(fl(origin) +
/// fl(h)·s) is off by δp ≤ 2u|origin| + 3u·h|s|. The warp: d = p − a adds u|a| (the anchor rounded)
/// + u|d|; √s and the division by s (GLSL: 2 and 2.5 ulp, an ulp ≤ 2u) and s's own rounding make
/// ≤ 8u|d| relative, and the stretch is at most 1/s; a + (…) and × invVoxel (rounded itself) add
/// u|a| + 3u|q|, q the unslumped point. The trilinear interpolant's gradient is ≤ √3·maxSlope
/// (MeltGrids), so the index error moves the body by that times δq; its seven lerps round ≤ 9u of
/// the corners (≤ band), the blend of two levels (its weight rounded) ≤ 8u·band, × s another
/// u·band, and the body is scaled by s. The puddle's exact distance is 1-Lipschitz in p (δd) and its
/// ~10 operations on lengths ≤ |d| + R + h add 10u of those. The smooth union's weights sum to 1,
/// so it passes on the larger of the two errors, plus 6u of |body| + |puddle| + k of its own.
double floatBound(const MeltGrids& g, const MeltState& st, const SampledLattice& frame, glm::ivec3 s) {
  const double u = kUnitRoundoff;
  const glm::dvec3 p = frame.position(s.x, s.y, s.z);
  const double dp = 2.0 * u * glm::length(frame.origin) + 3.0 * u * frame.cellSize * glm::length(glm::dvec3(s));
  const double a = glm::length(g.anchor);
  const glm::dvec3 dv = p - g.anchor;
  const double d = glm::length(dv);
  const double sc = st.heightScale;
  const glm::dvec3 q = g.anchor + glm::dvec3(dv.x * std::sqrt(sc), dv.y / sc, dv.z * std::sqrt(sc));
  const double dd = dp + u * a + u * d;
  const double dq = (dd + 8.0 * u * d) / sc + u * a + 3.0 * u * glm::length(q);
  const double band = g.bandWidth;
  const double body = sc * (std::sqrt(3.0) * g.maxSlope * dq + 17.0 * u * band) + u * band;
  if (!(st.puddleHeight > 0.0)) return body;
  const double puddle = dd + 10.0 * u * (d + st.puddleRadius + st.puddleHeight);
  return std::max(body, puddle) + 6.0 * u * (band + d + st.puddleRadius + st.joinRadius);
}

/// The bounds are first order and per operation; twice them leaves room for second-order terms
/// and a driver that uses all of GLSL's allowance (llvmpipe stays under 1/25 of it), and still
/// catches a real error: the GPU reading one level for both (gridB = gridA) at t = 5 is 1.7e-4 m
/// off, 320 times the bound; a trilinear weight on the wrong axis, 265 times at t = 0.
constexpr double kBoundSafety = 2.0;

class MeshMeltGpuTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { source_ = std::make_unique<sss::FieldSource>(meltingBunny()); }
  static void TearDownTestSuite() { source_.reset(); }
  void SetUp() override { context_ = gpu::GlContext::create(gpu::ContextOptions{}); }
  static std::unique_ptr<sss::FieldSource> source_;
  std::unique_ptr<gpu::GlContext> context_;
  gpu::ShaderLibrary library_;
};
std::unique_ptr<sss::FieldSource> MeshMeltGpuTest::source_;

// (a) The lattice the GPU fills is the CPU's field (FieldSource::at(t), i.e. MeshLevelSetField::
// melted(t): melt.glsl in double) at the same lattice points, within the float bound above at every
// sample, at 48³ points for each t.
TEST_F(MeshMeltGpuTest, LatticeFilledOnTheGpuIsTheCpuFieldAtTheSamePoints) {
  constexpr int kSamples = 48;
  GpuMeltField gpuMelt(library_);
  GpuDualContouring dc(library_, kSamples);
  const SampledLattice frame = source_->gpuLattice(kSamples);
  for (double t : kTimes) {
    const MeltAt at = *source_->meltAt(t);
    const std::unique_ptr<geometry::ScalarField> cpu = source_->at(t);
    gpuMelt.fill(dc, at, frame);
    const std::vector<float> values = dc.readLattice();
    ASSERT_EQ(values.size(), static_cast<std::size_t>(kSamples * kSamples * kSamples));
    int outside = 0, signs = 0, inside = 0;
    double worst = 0.0, worstRatio = 0.0;
    for (int z = 0; z < kSamples; ++z)
      for (int y = 0; y < kSamples; ++y)
        for (int x = 0; x < kSamples; ++x) {
          const double exact = cpu->value(frame.position(x, y, z));
          const double gpu = values[frame.index(x, y, z)];
          const double bound = kBoundSafety * floatBound(*at.grids, at.state, frame, {x, y, z});
          const double error = std::abs(gpu - exact);
          worst = std::max(worst, error);
          worstRatio = std::max(worstRatio, error / bound);
          outside += error > bound ? 1 : 0;
          signs += std::abs(exact) > bound && (gpu < 0.0) != (exact < 0.0) ? 1 : 0;
          inside += exact < 0.0 ? 1 : 0;
        }
    std::printf("[ melt gpu ] t = %g (f = %.2f, levels %u/%u blend %.2f, puddle %.2g m): largest |GPU − CPU| %.3g m, "
                "largest error/bound %.3f, %d samples inside\n",
                t, at.state.f, at.state.gridA, at.state.gridB, at.state.blend, at.state.puddleHeight, worst,
                worstRatio, inside);
    EXPECT_GT(inside, 100) << "t = " << t;
    EXPECT_EQ(outside, 0) << "t = " << t << ": samples off by more than the float bound";
    EXPECT_EQ(signs, 0) << "t = " << t;
  }
  EXPECT_EQ(dc.uploadCount(), 0u);
  EXPECT_EQ(dc.gpuFillCount(), std::size(kTimes));
  EXPECT_EQ(gpuMelt.gridUploadCount(), 1u);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

// (b) The NanoVDB read (PNanoVDB's C port over the bytes the GPU gets, melt.glsl's trilinear sample)
// is OpenVDB's own BoxSampler on the OpenVDB grid it was converted from, at random points in and
// around every smoothing level's band (outside it both give the background). OpenVDB interpolates in
// float (lerps a + w(b − a), ≤ 3u of the corners each, seven of them), melt.glsl here in double:
// ≤ 24u·band apart, and the world-to-index maps differ by double round-off only.
TEST_F(MeshMeltGpuTest, NanoVdbSampleIsOpenVdbsTrilinearSampleOfTheSameGrid) {
  const MeltAt at = *source_->meltAt(kMeltS);
  const MeltGrids& g = *at.grids;
  ASSERT_EQ(g.iterations, (std::vector<int>{0, 4, 8, 12}));
  const double bound = 24.0 * kUnitRoundoff * g.bandWidth + 1e-12;
  std::mt19937 rng(16);
  const glm::dvec3 lo = glm::dvec3(g.levelBounds.min) - 4.0 * g.voxelSize;
  const glm::dvec3 hi = glm::dvec3(g.levelBounds.max) + 4.0 * g.voxelSize;
  std::uniform_real_distribution<double> ux(lo.x, hi.x), uy(lo.y, hi.y), uz(lo.z, hi.z);
  for (int level = 0; level < static_cast<int>(g.levels.size()); ++level) {
    int beyond = 0, inBand = 0;
    double worst = 0.0;
    for (int i = 0; i < 20000; ++i) {
      const glm::dvec3 p(ux(rng), uy(rng), uz(rng));
      const double nano = geometry::meltLevelSample(g, level, p);
      const double open = geometry::meltLevelSampleByOpenVdb(g, level, p);
      worst = std::max(worst, std::abs(nano - open));
      beyond += std::abs(nano - open) > bound ? 1 : 0;
      inBand += std::abs(open) < 0.99 * g.bandWidth ? 1 : 0;
    }
    std::printf("[ melt gpu ] level %d (%d steps): largest |NanoVDB − OpenVDB| %.3g m over 20000 points, %d in the band\n",
                level, g.iterations[static_cast<std::size_t>(level)], worst, inBand);
    EXPECT_EQ(beyond, 0) << "level " << level;
    EXPECT_GT(inBand, 500) << "level " << level;
  }
}

// --- the renderer ---------------------------------------------------------------------------------

constexpr int kRes = 48;

/// Writes a preset with the melting bunny into `dir`; returns its path.
std::string meltingPreset(const test::TempDir& dir) {
  return dir.write("melting.json", R"({"camera": {"position": [0, 0.06, 0.3], "target": [0, 0.04, 0]},
      "lights": [{"type": "directional", "direction": [0, 1, 1], "irradiance": [3, 3, 3]}],
      "objects": [{"field": {"type": "mesh", "mesh": "data:bunny.ply", "melt_s": 10}, "scale": 0.1}]})")
      .string();
}

/// The settings of that preset at a small size with a coarse lattice.
std::vector<std::string> smallFieldSets(const std::string& placement) { return test::smallFieldSets(kRes, placement); }

/// Renders the frame at t, expecting no GL error.
void renderChecked(test::PresetSession& s, double t) {
  s.renderFrame(t);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

// (c) The renderer's melting frames come from the GPU fill and extract the mesh of the CPU-sampled
// path at the same t: the same lattice up to the float bound of (a), so the same triangles except
// where a sample within that bound of 0 flips sign (each flip changes at most the 12 edges around
// it, 2 triangles each), and vertices close to the other mesh: the mass point moves a crossing by
// δ/|Δv| of an edge (δ ≲ 1e-7 m against |Δv| ≳ 1e-4 m of a 2 mm cell where the surface crosses:
// 1e-3 cells); the QEF's discrete stencil choice and regularised solve amplify a normal's change up
// to 100× (blob_gpu_gltest.cpp): 0.05 cells.
class MeltGpuRendererPlacement : public ::testing::TestWithParam<const char*> {};

TEST_P(MeltGpuRendererPlacement, MeltingFramesAreFilledOnTheGpuAndMatchTheCpuSampledPath) {
  const std::string placement = GetParam();
  const double hausdorffCells = placement == "mass" ? 1e-3 : 0.05;
  const test::TempDir dir;
  test::PresetSession s(meltingPreset(dir), smallFieldSets(placement));
  const auto& objects = s.scene().objects;
  const auto field = std::find_if(objects.begin(), objects.end(),
                                  [](const sss::SceneObject& o) { return o.shape == sss::ShapeKind::Field; });
  ASSERT_NE(field, objects.end());
  const sss::FieldSource source(*field);  // the CPU path's own (its grids built again)
  int frames = 0;
  for (double t : {2.0, 5.0, 10.0}) {
    renderChecked(s, t);
    ++frames;
    const sss::DrawItem* item = test::fieldItem(s.renderer());
    ASSERT_NE(item, nullptr);
    const GpuDualContouring& rendered = *item->field;
    EXPECT_EQ(rendered.uploadCount(), 0u) << "a melting lattice was sampled on the CPU and uploaded";
    EXPECT_EQ(rendered.gpuFillCount(), static_cast<std::size_t>(frames));

    const test::FieldComparison c =
        test::compareWithCpuSampledPath(rendered, source, t, kRes, s.shaders(), s.settings().fieldPlacement);
    const SampledLattice& cpuLattice = c.cpuLattice;

    const MeltAt at = *source.meltAt(t);
    int nearZero = 0;
    for (int z = 0; z < kRes; ++z)
      for (int y = 0; y < kRes; ++y)
        for (int x = 0; x < kRes; ++x)
          nearZero += std::abs(cpuLattice.at(x, y, z)) <= kBoundSafety * floatBound(*at.grids, at.state, cpuLattice, {x, y, z})
                          ? 1
                          : 0;
    std::printf("[ melt gpu ] renderer %s t = %g at %d^3: %zu triangles (CPU path %zu), Hausdorff %.2e cells, "
                "%d samples within the bound of 0\n",
                placement.c_str(), t, kRes, c.gpuMesh.triangles.size(), c.cpuMesh.triangles.size(), c.hausdorff,
                nearZero);
    ASSERT_GT(c.cpuMesh.triangles.size(), 1000u);
    EXPECT_EQ(test::badEdges(c.gpuMesh), 0) << "t = " << t;
    EXPECT_GT(test::signedVolume(c.gpuMesh), 0.0) << "t = " << t;
    EXPECT_LE(std::abs(c.triangleDifference), 24L * nearZero) << "t = " << t;
    EXPECT_LE(c.hausdorff, hausdorffCells) << placement << ", t = " << t;
  }
}

INSTANTIATE_TEST_SUITE_P(Placements, MeltGpuRendererPlacement, ::testing::Values("mass", "qef"));

// (d) The static grids reach the GPU once per preset load: one upload at the first frame, none for
// the frames after (new t, the same t again, back in time), and no lattice is ever uploaded.
TEST(MeltGpuRenderer, StaticGridsAreUploadedOnceAndNothingPerFrame) {
  const test::TempDir dir;
  test::PresetSession s(meltingPreset(dir), smallFieldSets("mass"));
  EXPECT_EQ(s.renderer().fieldObjects().meltGridUploads(), 0u);
  const double times[] = {0.0, 1.0, 4.0, 4.0, 9.5, 2.0, 30.0};
  for (std::size_t i = 0; i < std::size(times); ++i) {
    renderChecked(s, times[i]);
    EXPECT_EQ(s.renderer().fieldObjects().meltGridUploads(), 1u) << "after frame " << i;
    const sss::DrawItem* item = test::fieldItem(s.renderer());
    ASSERT_NE(item, nullptr) << "after frame " << i;
    EXPECT_EQ(item->field->uploadCount(), 0u) << "after frame " << i;
  }
  // The same t twice is not filled again (the field is not stale): 6 fills for 7 frames.
  EXPECT_EQ(test::fieldItem(s.renderer())->field->gpuFillCount(), std::size(times) - 1);
}

}  // namespace
}  // namespace tallow
