// Melting of mesh-derived level sets (issue 4, point 1: "imported shapes … can melt too"). A box
// of known size makes the expectations analytic: the slump is an affine map of determinant 1, the
// puddle a disc of known radius.
#include "geometry/cpu_mesher.h"
#include "geometry/grid_sampler.h"
#include "geometry/mesh_level_set_field.h"
#include "geometry/primitives.h"

#include <gtest/gtest.h>

#include "support/mesh_checks.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>

namespace tallow::geometry {
namespace {

using test::badEdges;
using test::countComponents;
using test::signedVolume;

constexpr double kWidth = 0.04, kHeight = 0.08;  // metres: a 4 × 8 × 4 cm block, base at y = 0
constexpr int kLevelSetResolution = 64;          // voxels along the height: 1.25 mm
constexpr int kLattice = 96;

MeshLevelSetField block() {
  TriangleMesh box = makeBox();  // unit cube centred on the origin
  for (glm::vec3& p : box.positions)
    p = p * glm::vec3(kWidth, kHeight, kWidth) + glm::vec3(0.0f, 0.5f * static_cast<float>(kHeight), 0.0f);
  return MeshLevelSetField(box, kLevelSetResolution);
}

TriangleMesh meshOf(const ScalarField& field) { return meshOnCpu(field, kLattice); }

double top(const TriangleMesh& mesh) {
  double y = -1e30;
  for (const glm::vec3& p : mesh.positions) y = std::max(y, static_cast<double>(p.y));
  return y;
}

double halfWidthX(const TriangleMesh& mesh) {
  double x = 0.0;
  for (const glm::vec3& p : mesh.positions) x = std::max(x, std::abs(static_cast<double>(p.x)));
  return x;
}

TEST(MeshMelting, SlumpLowersTheTopAndKeepsTheVolume) {
  const MeshLevelSetField base = block();
  MeltParams p;
  p.puddleHeight = 0.0;
  p.smoothingIterations = 0;
  const auto start = std::chrono::steady_clock::now();
  const MeshLevelSetField half = base.melted(0.5 * p.durationS, p);
  std::printf("[ melt ] slump at f = 0.5: %.0f ms\n",
              std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  const TriangleMesh before = meshOf(base), after = meshOf(half);
  ASSERT_EQ(badEdges(after), 0);
  // y × s about the base, x and z × 1/√s: s = 1 − 0.4 · 0.5 = 0.8, determinant 1.
  const double s = 0.8, voxel = base.voxelSize();
  EXPECT_NEAR(top(after), top(before) * s, 1.5 * voxel);
  EXPECT_NEAR(halfWidthX(after), halfWidthX(before) / std::sqrt(s), 1.5 * voxel);
  EXPECT_NEAR(signedVolume(after) / signedVolume(before), 1.0, 0.01);
}

TEST(MeshMelting, PuddleSpreadsFromTheFootprint) {
  const MeshLevelSetField base = block();
  MeltParams p;
  p.slump = 0.0;
  p.smoothingIterations = 0;
  const MeshLevelSetField melted = base.melted(p.durationS, p);
  // f = 1: a disc of radius 0.02 · (1 + 0.6) = 3.2 cm and thickness 0.06 · 8 cm = 4.8 mm.
  const double radius = 0.5 * kWidth * (1.0 + p.puddleSpread), thickness = p.puddleHeight * kHeight;
  const double voxel = base.voxelSize();
  EXPECT_LT(melted.value({radius - 2.0 * voxel, 0.5 * thickness, 0.0}), 0.0);  // in the puddle
  EXPECT_GT(melted.value({radius + 2.0 * voxel, 0.5 * thickness, 0.0}), 0.0);  // beyond its rim
  EXPECT_GT(melted.value({radius - 2.0 * voxel, thickness + 2.0 * voxel, 0.0}), 0.0);  // above it
  EXPECT_GT(base.value({radius - 2.0 * voxel, 0.5 * thickness, 0.0}), 0.0);  // not there before
  const TriangleMesh mesh = meshOf(melted);
  EXPECT_EQ(badEdges(mesh), 0);
  EXPECT_EQ(countComponents(mesh), 1);
  EXPECT_NEAR(halfWidthX(mesh), radius, 2.0 * voxel);
}

TEST(MeshMelting, SinksMonotonicallyAndStaysClosed) {
  const MeshLevelSetField base = block();
  const MeltParams p;  // slump, puddle and smoothing together
  double previousTop = 1e30;
  for (double t : {0.0, 5.0, 10.0, 15.0, 20.0, 30.0}) {
    SCOPED_TRACE("t = " + std::to_string(t));
    const TriangleMesh mesh = meshOf(base.melted(t, p));
    EXPECT_EQ(badEdges(mesh), 0);
    EXPECT_EQ(countComponents(mesh), 1);
    EXPECT_GT(signedVolume(mesh), 0.0);
    const double y = top(mesh);
    if (t <= p.durationS) EXPECT_LT(y, previousTop);
    else EXPECT_DOUBLE_EQ(y, previousTop);  // clamped at f = 1
    previousTop = y;
  }
  // Fully melted: at most (1 − slump) of the height, minus what the smoothing rounds off.
  EXPECT_LT(previousTop, (1.0 - p.slump) * kHeight + base.voxelSize());
}

TEST(MeshMelting, SameTimeSameFieldWhetherPlayedOrJumped) {
  const MeshLevelSetField base = block();
  const MeltParams p;
  const MeshLevelSetField first = base.melted(7.0, p);
  const MeshLevelSetField other = base.melted(3.0, p);  // evicts the cached t = 7
  const MeshLevelSetField again = base.melted(7.0, p);   // rebuilt from the unmelted level set
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.04, 0.04), v(-0.01, 0.09);
  int differ = 0, differFromOther = 0;
  for (int i = 0; i < 2000; ++i) {
    const glm::dvec3 q(u(rng), v(rng), u(rng));
    differ += first.value(q) != again.value(q) ? 1 : 0;
    differFromOther += first.value(q) != other.value(q) ? 1 : 0;
  }
  EXPECT_EQ(differ, 0);
  EXPECT_GT(differFromOther, 100);  // and t = 3 is a different shape
  // t ≤ 0 is the unmelted field itself.
  const MeshLevelSetField zero = base.melted(0.0, p);
  for (int i = 0; i < 200; ++i) {
    const glm::dvec3 q(u(rng), v(rng), u(rng));
    EXPECT_EQ(zero.value(q), base.value(q));
  }
}

TEST(MeshMelting, RejectsBadParameters) {
  const MeshLevelSetField base = block();
  MeltParams p;
  p.durationS = 0.0;
  EXPECT_THROW(base.melted(1.0, p), std::invalid_argument);
  p = {};
  p.slump = 0.95;
  EXPECT_THROW(base.melted(1.0, p), std::invalid_argument);
  p = {};
  p.smoothingIterations = -1;
  EXPECT_THROW(base.melted(1.0, p), std::invalid_argument);
  EXPECT_THROW(base.melted(std::nan(""), MeltParams{}), std::invalid_argument);
}

}  // namespace
}  // namespace tallow::geometry
