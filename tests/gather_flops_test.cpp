// The FLOP count of the gather (app/bench_report/): the counting scalar counts GLM's vector
// functions operation by operation, the counted sample computes exactly what the float
// instantiation of the same shared lines computes, and the three BSSRDF models order by the work
// their formulas do.
#include <gtest/gtest.h>

#include "app/bench_report/counted_real.h"
#include "app/bench_report/gather_flops.h"
#include "sss/bssrdf/material.h"
#include "gpu/glsl_shared.h"

#include <cstdint>
#include <cstdio>

// The shared estimator lines with the counting scalar, to count a point light's extras alone.
namespace tallow::flops::test_counted {
using uint = std::uint32_t;
using real = CountedReal;
#include "gpu/glsl_real_types.inc"
#include "sss/bssrdf/bssrdf_models.inc"
#include "shaders/maps/estimator.glsl"
}  // namespace tallow::flops::test_counted

namespace tallow {
namespace {

namespace counted = flops::test_counted;

using flops::CountedReal;
using V3 = glm::vec<3, CountedReal>;

sss::Material marble() {
  const auto m = sss::MaterialTable::load(std::filesystem::path(TALLOW_TEST_DATA_DIR) / "materials.csv").find("Marble");
  EXPECT_TRUE(m.has_value());
  return m.value_or(sss::Material{});
}

TEST(GatherFlops, CountsGlmVectorFunctionsOperationByOperation) {
  const V3 a(CountedReal(1.0f), CountedReal(2.0f), CountedReal(3.0f));
  const V3 b(CountedReal(-2.0f), CountedReal(0.5f), CountedReal(4.0f));
  flops::reset();
  const CountedReal d = glm::dot(a, b);
  EXPECT_EQ(d.value(), 11.0f);
  EXPECT_EQ(flops::counts().mul, 3u);  // x·x', y·y', z·z'
  EXPECT_EQ(flops::counts().add, 2u);  // their sum
  flops::reset();
  const V3 c = glm::cross(a, b);
  EXPECT_EQ(c.x.value(), 2.0f * 4.0f - 3.0f * 0.5f);
  EXPECT_EQ(flops::counts().mul, 6u);
  EXPECT_EQ(flops::counts().add, 3u);  // subtractions count as additions
  flops::reset();
  const V3 n = glm::normalize(a);
  EXPECT_NEAR(n.z.value(), 3.0f / std::sqrt(14.0f), 1e-6f);
  // dot (3 mul, 2 add), one inverse square root, then 3 products.
  EXPECT_EQ(flops::counts().mul, 6u);
  EXPECT_EQ(flops::counts().add, 2u);
  EXPECT_EQ(flops::counts().special, 1u);
  EXPECT_EQ(flops::counts().flops(), 9u);
  flops::reset();
  const CountedReal m = max(-a.x, CountedReal(0.0f));
  EXPECT_EQ(m.value(), 0.0f);
  EXPECT_EQ(flops::counts().flops(), 0u);  // sign flips and comparisons are no FLOPs
  EXPECT_EQ(flops::counts().other, 1u);
}

TEST(GatherFlops, CountedSampleComputesWhatTheFloatShaderLinesCompute) {
  const flops::GatherFlops g = flops::countGatherFlops(marble(), sss::BssrdfModel::Directional, 32);
  // Bit for bit: the counting type runs the same float operations in the same order.
  EXPECT_EQ(g.maxValueDifference, 0.0);
  for (const flops::LoopFlops& f : {g.directional, g.point}) {
    EXPECT_EQ(f.samples, 31);  // the spans between the 32 samples' look-ups
    EXPECT_GT(f.flopsMean, 0.0);
    EXPECT_DOUBLE_EQ(3.0 * f.flopsMean, f.flopsPerSharedSample);
    EXPECT_LE(double(f.flopsSharedMin), f.flopsPerSharedSample);
    EXPECT_GE(double(f.flopsSharedMax), f.flopsPerSharedSample);
    EXPECT_NEAR(f.addMean + f.mulMean + f.divMean + f.specialMean, f.flopsMean, 1e-9);
    // At least the radial sample's log, the dipole's exponentials and square roots.
    EXPECT_GE(f.specialMean, 4.0);
    EXPECT_GT(f.flopsPerTexel, 0.0);  // the three bands' coefficients at least
  }
}

TEST(GatherFlops, ThePointLightsLoopCountsItsLookUpAndAreaRatio) {
  // A point light's sample does all a directional sample does (the draw, x_i, three terms; the
  // weight's division, as the projected-area division) and, on top, the stereographic look-up
  // direction (Eqs. 13–14), the normalised look-up, E = I/d² and the stereographic area ratio. Those
  // extras counted here on their own, with the counting scalar on the same shared lines, bound the
  // difference from below: a counter that left the point loop out, or ran the directional one for
  // it, fails.
  const flops::GatherFlops g = flops::countGatherFlops(marble(), sss::BssrdfModel::Directional, 32);
  const V3 xo(CountedReal(0.0f)), no(CountedReal(0.0f), CountedReal(0.0f), CountedReal(1.0f));
  const V3 xj(CountedReal(2.0f), CountedReal(1.0f), CountedReal(0.0f));
  const V3 xl(CountedReal(0.0f), CountedReal(0.0f), CountedReal(15.0f));
  flops::reset();
  const V3 dir = counted::sssStereographicLookupDirection(xo, xj, xl);
  const V3 unit = glm::normalize(dir);
  const V3 xi = xl + CountedReal(15.0f) * unit;
  const V3 ni = -unit;
  flops::reset();
  (void)counted::sssStereographicLookupDirection(xo, xj, xl);
  (void)glm::normalize(dir);
  const V3 toLight = xl - xi;
  (void)(glm::dot(toLight, toLight) / CountedReal(1e6f));
  (void)counted::sssStereographicAreaRatio(xo, no, xj, xl, xi, ni);
  const std::uint64_t extras = flops::counts().flops();
  std::printf("[ flops ] per shared sample: directional %.1f, point %.1f; the point light's extras %llu\n",
              g.directional.flopsPerSharedSample, g.point.flopsPerSharedSample,
              static_cast<unsigned long long>(extras));
  EXPECT_GT(extras, 30u);
  EXPECT_GE(g.point.flopsPerSharedSample, g.directional.flopsPerSharedSample + double(extras));
}

TEST(GatherFlops, ModelsOrderByTheirWork) {
  const sss::Material m = marble();
  const double standard = flops::countGatherFlops(m, sss::BssrdfModel::Standard, 8).directional.flopsMean;
  const double directional = flops::countGatherFlops(m, sss::BssrdfModel::Directional, 8).directional.flopsMean;
  const double pbd = flops::countGatherFlops(m, sss::BssrdfModel::PhotonBeamDiffusion, 8).directional.flopsMean;
  // The standard dipole is two exponential point sources (Jensen et al. 2001); the directional
  // dipole two ray sources of Eq. 20, each a longer expression, and its virtual-source geometry
  // (Frisvad et al. 2014); photon beam diffusion integrates point sources along the beam by
  // Gauss–Legendre quadrature (Habel et al. 2013).
  EXPECT_LT(standard, directional);
  EXPECT_LT(directional, pbd);
  EXPECT_GT(pbd, 2.0 * directional);
}

TEST(GatherFlops, RejectsFewerThanTwoSamples) {
  EXPECT_THROW(flops::countGatherFlops(marble(), sss::BssrdfModel::Directional, 1), std::invalid_argument);
}

}  // namespace
}  // namespace tallow
