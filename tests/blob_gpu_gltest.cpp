// The blob on the GPU (issue 16, points 1 and 3): Φ_t and its analytic gradient evaluated in GLSL
// from the blobs' centres at t (shaders/fields/blob.glsl, the lines BlobField evaluates in double),
// against BlobField at the same points; and the renderer's blob frames, filled on the GPU with no
// lattice uploaded, against the CPU-sampled path at the same t.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "geometry/blob_field.h"
#include "geometry/gpu_blob_field.h"
#include "geometry/gpu_dual_contouring.h"
#include "geometry/grid_sampler.h"
#include "gpu/gl_context.h"
#include "gpu/shader_library.h"
#include "sss/field_source.h"
#include "sss/renderer.h"
#include "support/field_compare.h"
#include "support/render_support.h"

namespace tallow {
namespace {

using geometry::BlobField;
using geometry::BlobParams;
using geometry::GpuBlobField;
using geometry::GpuDualContouring;
using geometry::NormalSource;
using geometry::SampledLattice;

constexpr double kUnitRoundoff = 0x1p-24;  ///< u of IEEE float: a correctly rounded operation is within u relative

/// Times that cover the blob's states: one merged ball (0), split apart (3.95, as in
/// fields_test.cpp), mixed states, and a large t whose phases are reduced on the CPU.
constexpr double kTimes[] = {0.0, 1.7, 3.95, 11.3, 2000.5};

/// First-order bounds on the error of shaders/fields/blob.glsl evaluated in float at p (world
/// units), against the exact value, when the shader's q = p / scale is off by at most `dq` (unscaled
/// units). Operation by operation, with u the float unit roundoff: each centre rounded to float
/// (u|c|); d = q − c (u|d|); dot(d, d) (3u relative) and σ·(…) (u): x = σ‖d‖² is off by
/// 2σ‖d‖·δd + 4u·x; GLSL's exp is within (3 + 2|x|) ulp (GLSL 4.50 §4.7.1; an ulp is at most 2u
/// relative), so each term e = exp(−x) is off by e·(δx + (3 + 2x)·2u); the four additions and
/// iso − Φ add u of the partial sums each. For the gradient Σ 2σ e d (before the common 1/scale,
/// which does not turn it): per term 2σ(δe‖d‖ + e·δd + 3u·e‖d‖) and u per addition. σ = 4 and
/// iso = 0.5 are exact in float; scale is not, which `dq` carries (q = p / scale).
struct FloatErrorBound {
  double value = 0.0;     ///< |float − exact| of iso − Φ_t
  double gradient = 0.0;  ///< ‖float − exact‖ of Σ 2σ e d (unscaled gradient)
  double gradientLength = 0.0;  ///< ‖Σ 2σ e d‖, exact
};

FloatErrorBound floatErrorBound(const BlobField& blob, glm::dvec3 p, double dq) {
  const double u = kUnitRoundoff;
  const BlobParams& params = blob.params();
  const double sigma = params.sigma;
  const glm::dvec3 q = p / params.scale;
  FloatErrorBound b;
  double phi = 0.0, terms = 0.0;
  glm::dvec3 g(0.0);
  for (int i = 0; i < BlobParams::kBlobCount; ++i) {
    const glm::dvec3 c = blob.unscaledCentre(i), d = q - c;
    const double r = glm::length(d), x = sigma * r * r, e = std::exp(-x);
    const double dd = dq + u * glm::length(c) + u * r;
    const double dx = 2.0 * sigma * r * dd + 4.0 * u * x;
    const double de = e * (dx + (3.0 + 2.0 * x) * 2.0 * u);
    b.value += de;
    b.gradient += 2.0 * sigma * (de * r + e * dd + 3.0 * u * e * r);
    phi += e;
    terms += 2.0 * sigma * e * r;
    g += 2.0 * sigma * e * d;
  }
  b.value += 5.0 * u * (params.iso + phi);
  b.gradient += 4.0 * u * terms;
  b.gradientLength = glm::length(g);
  return b;
}

/// |δq| of the lattice fill: sample s at fl(fl(origin) + fl(fl(h)·s)) is off by at most
/// 2u|origin| + 3u·h|s| per component (world units), then q = p / fl(scale) adds 2u|q|.
double latticeDq(const SampledLattice& frame, glm::ivec3 s, double scale) {
  const double u = kUnitRoundoff;
  const double dp = 2.0 * u * glm::length(frame.origin) + 3.0 * u * frame.cellSize * glm::length(glm::dvec3(s));
  return dp / scale + 2.0 * u * glm::length(frame.position(s.x, s.y, s.z)) / scale;
}

/// The bounds are first order and per operation; twice them leaves room for the second-order
/// terms and for a driver's exp that uses all of GLSL's allowance, and still catches any real error:
/// a centre off by one float ulp of its own already moves values near the surface by more.
constexpr double kBoundSafety = 2.0;

class BlobGpuTest : public ::testing::Test {
 protected:
  void SetUp() override { context_ = gpu::GlContext::create(gpu::ContextOptions{}); }
  std::unique_ptr<gpu::GlContext> context_;
  gpu::ShaderLibrary library_;
};

// (a) The lattice the GPU fills is BlobField::value at the same lattice points, within the float
// bound above at every sample (not a blanket tolerance: the bound is ~1e-7 far from the blobs and
// grows only with the terms' own size).
TEST_F(BlobGpuTest, LatticeFilledOnTheGpuIsBlobFieldValueAtTheSamePoints) {
  constexpr int kSamples = 40;
  GpuBlobField gpuBlob(library_);
  GpuDualContouring dc(library_, kSamples);
  for (double t : kTimes) {
    const BlobField blob(t);
    const SampledLattice frame = geometry::latticeOver(blob.bounds(), kSamples);
    gpuBlob.fill(dc, blob, frame);
    const std::vector<float> values = dc.readLattice();
    ASSERT_EQ(values.size(), static_cast<std::size_t>(kSamples * kSamples * kSamples));
    int outside = 0, signs = 0;
    double worst = 0.0, worstRatio = 0.0;
    for (int z = 0; z < kSamples; ++z)
      for (int y = 0; y < kSamples; ++y)
        for (int x = 0; x < kSamples; ++x) {
          const glm::dvec3 p = frame.position(x, y, z);
          const double exact = blob.value(p);
          const double gpu = values[frame.index(x, y, z)];
          const double bound =
              kBoundSafety * floatErrorBound(blob, p, latticeDq(frame, {x, y, z}, blob.params().scale)).value;
          const double error = std::abs(gpu - exact);
          worst = std::max(worst, error);
          worstRatio = std::max(worstRatio, error / bound);
          outside += error > bound ? 1 : 0;
          signs += std::abs(exact) > bound && (gpu < 0.0) != (exact < 0.0) ? 1 : 0;
        }
    std::printf("[ blob gpu ] t = %g: largest |GPU − BlobField::value| %.3g, largest error/bound %.3f\n", t, worst,
                worstRatio);
    EXPECT_EQ(outside, 0) << "t = " << t << ": samples off by more than the float bound";
    EXPECT_EQ(signs, 0) << "t = " << t;
  }
  EXPECT_EQ(dc.uploadCount(), 0u);
  EXPECT_EQ(dc.gpuFillCount(), std::size(kTimes));
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

/// Angle (radians) between two vectors.
double angle(glm::dvec3 a, glm::dvec3 b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

// (b) The normals of an extracted blob mesh are the analytic gradient: at every vertex within the
// float bound of BlobField::gradient's direction there (the bound over ‖g‖, plus 4u for the
// normalisation and the stored float). The lattice's finite differences, the path of the other
// fields, miss that bound at most vertices (their error is a fraction of a degree), so the test
// tells the two apart.
TEST_F(BlobGpuTest, VertexNormalsAreTheAnalyticGradientAtTheVertices) {
  constexpr int kSamples = 48;
  GpuBlobField gpuBlob(library_);
  GpuDualContouring analytic(library_, kSamples, geometry::kDefaultPlacement, NormalSource::BlobGradient);
  GpuDualContouring lattice(library_, kSamples, geometry::kDefaultPlacement, NormalSource::LatticeGradient);
  for (double t : kTimes) {
    const BlobField blob(t);
    const SampledLattice frame = geometry::latticeOver(blob.bounds(), kSamples);
    for (GpuDualContouring* dc : {&analytic, &lattice}) {
      gpuBlob.fill(*dc, blob, frame);
      dc->extract();
    }
    const geometry::TriangleMesh mesh = analytic.readBack(), byLattice = lattice.readBack();
    ASSERT_GT(mesh.positions.size(), 100u);
    // The same lattice gives the same vertices, though not in the same order (atomic counters).
    ASSERT_EQ(mesh.positions.size(), byLattice.positions.size());
    /// Angle of each vertex normal of `m` to the exact gradient there, and the float bound on it.
    auto check = [&](const geometry::TriangleMesh& m, double& worstAngle) {
      int beyond = 0;
      for (std::size_t v = 0; v < m.positions.size(); ++v) {
        const glm::dvec3 p(m.positions[v]);  // the float position the shader evaluated at
        const FloatErrorBound b = floatErrorBound(blob, p, 2.0 * kUnitRoundoff * glm::length(p) / blob.params().scale);
        const double bound = kBoundSafety * (b.gradient / b.gradientLength + 4.0 * kUnitRoundoff);
        const double a = angle(glm::dvec3(m.normals[v]), blob.gradient(p));
        worstAngle = std::max(worstAngle, a);
        beyond += a > bound ? 1 : 0;
      }
      return beyond;
    };
    double worst = 0.0, worstLattice = 0.0;
    const int outside = check(mesh, worst), latticeOutside = check(byLattice, worstLattice);
    std::printf("[ blob gpu ] t = %g: %zu vertices, largest normal angle: analytic %.3g rad, lattice %.3g rad "
                "(%d of them beyond the float bound)\n",
                t, mesh.positions.size(), worst, worstLattice, latticeOutside);
    EXPECT_EQ(outside, 0) << "t = " << t << ": normals off the analytic gradient by more than the float bound";
    EXPECT_GT(latticeOutside, static_cast<int>(mesh.positions.size() / 2)) << "t = " << t;
  }
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

// --- the renderer ---------------------------------------------------------------------------------

constexpr int kRes = 48;

/// The settings of a preset at a small size with a coarse lattice.
std::vector<std::string> smallFieldSets(const std::string& placement = "qef") { return test::smallFieldSets(kRes, placement); }

/// Renders the frame at t, expecting no GL error; returns its timings.
sss::FrameTimings renderChecked(test::PresetSession& s, double t) {
  const sss::FrameTimings timings = s.renderFrame(t);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  return timings;
}

double passCpuMs(const sss::FrameTimings& t, const std::string& name) {
  for (const gpu::PassTiming& p : t.passes)
    if (p.name == name) return p.cpuMs;
  return -1.0;
}

// (c) The renderer's blob frames come from the GPU fill (no lattice uploaded, normals analytic) and
// extract the mesh of the CPU-sampled path at the same t: the same lattice up to the float bound,
// so the same triangles except where a sample within that bound of 0 flips sign (each flip changes
// at most the 12 edges around that sample, 2 triangles each), and vertices close to the other mesh.
// With the mass point a value error δ (≲ 1e-6) moves a crossing by δ / |Δv| of an edge, |Δv| over a
// cell ≳ 0.01 where the surface crosses (measured ~1e-5 cells): 1e-3 cells. The QEF's normals
// choose their stencil by comparing second differences (qef.glsl, DC_ENO_RATIO), a discrete choice
// that a value error can tip, and the regularised solve moves the vertex by up to 1/σ_n² = 100 times
// the normal's change (measured 2e-3 cells at t = 1): 0.05 cells, a third of the QEF's own
// distance to a cube's edges (dual_contouring_gltest.cpp) and far from any change of topology.
class BlobGpuRendererPlacement : public ::testing::TestWithParam<const char*> {};

TEST_P(BlobGpuRendererPlacement, BlobFramesAreFilledOnTheGpuAndMatchTheCpuSampledPath) {
  const std::string placement = GetParam();
  const double hausdorffCells = placement == "mass" ? 1e-3 : 0.05;
  test::PresetSession s("blob", smallFieldSets(placement));
  int frames = 0;
  for (double t : {1.0, 3.95, 11.3}) {
    const sss::FrameTimings timings = renderChecked(s, t);
    ++frames;
    const sss::DrawItem* item = test::fieldItem(s.renderer());
    ASSERT_NE(item, nullptr);
    const GpuDualContouring& rendered = *item->field;
    EXPECT_EQ(rendered.uploadCount(), 0u) << "a blob lattice was sampled on the CPU and uploaded";
    EXPECT_EQ(rendered.gpuFillCount(), static_cast<std::size_t>(frames));
    EXPECT_EQ(rendered.normalSource(), NormalSource::BlobGradient);

    const sss::FieldSource source(s.scene().objects[static_cast<std::size_t>(item->objectIndex)]);
    const test::FieldComparison c =
        test::compareWithCpuSampledPath(rendered, source, t, kRes, s.shaders(), s.settings().fieldPlacement);
    const SampledLattice& cpuLattice = c.cpuLattice;

    // Samples that may flip: within the float bound of 0 (the bound at the sample, as in test (a)).
    const BlobField blob = *source.blobAt(t);
    int nearZero = 0;
    for (int z = 0; z < kRes; ++z)
      for (int y = 0; y < kRes; ++y)
        for (int x = 0; x < kRes; ++x) {
          const glm::dvec3 p = cpuLattice.position(x, y, z);
          const double bound = kBoundSafety *
                               floatErrorBound(blob, p, latticeDq(cpuLattice, {x, y, z}, blob.params().scale)).value;
          nearZero += std::abs(blob.value(p)) <= bound ? 1 : 0;
        }
    std::printf("[ blob gpu ] renderer %s t = %g at %d^3: %zu triangles (CPU path %zu), Hausdorff %.2e cells, "
                "%d samples within the bound of 0; field.sample %.3f ms CPU (llvmpipe, not asserted)\n",
                placement.c_str(), t, kRes, c.gpuMesh.triangles.size(), c.cpuMesh.triangles.size(), c.hausdorff,
                nearZero, passCpuMs(timings, "field.sample"));
    ASSERT_GT(c.cpuMesh.triangles.size(), 1000u);
    EXPECT_LE(std::abs(c.triangleDifference), 24L * nearZero) << "t = " << t;
    EXPECT_LE(c.hausdorff, hausdorffCells) << placement << ", t = " << t;
  }
}

INSTANTIATE_TEST_SUITE_P(Placements, BlobGpuRendererPlacement, ::testing::Values("mass", "qef"));

// The candle goes the same way since issue 16's point 2 (tests/candle_gpu_gltest.cpp has its
// checks): filled on the GPU from its shape at t, analytic normals, nothing uploaded.
TEST(BlobGpuRenderer, CandleTakesTheSameGpuPath) {
  test::PresetSession s("candle", smallFieldSets());
  renderChecked(s, 0.0);
  const sss::DrawItem* item = test::fieldItem(s.renderer());
  ASSERT_NE(item, nullptr);
  const GpuDualContouring& rendered = *item->field;
  EXPECT_EQ(rendered.uploadCount(), 0u);
  EXPECT_EQ(rendered.gpuFillCount(), 1u);
  EXPECT_EQ(rendered.normalSource(), NormalSource::CandleGradient);
}

}  // namespace
}  // namespace tallow
