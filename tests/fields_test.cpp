// Scalar fields (blob), lattice sampling and the OpenVDB CPU reference mesher; no GL.
#include "geometry/blob_field.h"
#include "geometry/cpu_mesher.h"
#include "geometry/grid_sampler.h"

#include <gtest/gtest.h>

#include "support/mesh_checks.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <numeric>
#include <random>
#include <string>
#include <utility>

namespace tallow::geometry {
namespace {

using test::badEdges;
using test::countComponents;
using test::edgeUses;
using test::faceCross;
using test::signedVolume;
using test::SphereField;

Aabb cube(glm::dvec3 centre, double half) {
  Aabb box;
  box.extend(glm::vec3(centre - half));
  box.extend(glm::vec3(centre + half));
  return box;
}

// ---------------------------------------------------------------------------------------------
// Blob field

/// Points near the surface of each blob (where the gradient is well away from zero).
std::vector<glm::dvec3> probePoints(const BlobField& field) {
  const double lone = std::sqrt(std::log(1.0 / field.params().iso) / field.params().sigma) * field.params().scale;
  const glm::dvec3 dirs[] = {{1, 0, 0}, {0, -1, 0}, {0, 0, 1}, glm::normalize(glm::dvec3(-1, 1, 1))};
  std::vector<glm::dvec3> points;
  for (int i = 0; i < BlobParams::kBlobCount; ++i)
    for (const glm::dvec3& d : dirs) points.push_back(field.centre(i) + lone * d);
  return points;
}

TEST(BlobField, AnalyticGradientMatchesCentralDifferences) {
  for (double t : {0.0, 1.3, 4.7, 123.4}) {
    const BlobField field(t);
    for (const glm::dvec3& p : probePoints(field)) {
      const glm::dvec3 analytic = field.gradient(p);
      const glm::dvec3 numeric = field.ScalarField::gradient(p);  // the base class: central differences
      // 1e-6 relative: the central-difference error (step² · Φ''' and round-off) is ~1e-9 here.
      EXPECT_LE(glm::length(analytic - numeric), 1e-6 * glm::length(analytic)) << "t=" << t;
    }
  }
}

// The same check at random points of the lattice's box, where the field ranges from deep inside to
// far outside (shaders/fields/blob.glsl's gradient, which BlobField::gradient evaluates, against
// differences of its value: two separate functions of the shared file). Points where the gradient
// is below 1% of its largest value over the box (far from every blob, or at a saddle) are skipped:
// there the central difference's round-off (~1e-16 / step) is no longer small relative to ‖∇‖.
TEST(BlobField, AnalyticGradientMatchesCentralDifferencesAtRandomPoints) {
  std::mt19937 rng(16);
  for (double t : {0.0, 3.95, 11.3}) {
    const BlobField field(t);
    const Aabb box = field.bounds();
    std::uniform_real_distribution<double> ux(box.min.x, box.max.x), uy(box.min.y, box.max.y), uz(box.min.z, box.max.z);
    // The largest ‖∇‖ of one blob: 2σ r e^{−σr²} at r = 1/√(2σ), per unscaled unit.
    const double largest = std::sqrt(2.0 * field.params().sigma) * std::exp(-0.5) / field.params().scale;
    int checked = 0;
    for (int i = 0; i < 2000; ++i) {
      const glm::dvec3 p(ux(rng), uy(rng), uz(rng));
      const glm::dvec3 analytic = field.gradient(p);
      if (glm::length(analytic) < 0.01 * largest) continue;
      ++checked;
      EXPECT_LE(glm::length(analytic - field.ScalarField::gradient(p)), 1e-6 * glm::length(analytic))
          << "t=" << t << " at " << p.x << ", " << p.y << ", " << p.z;
    }
    EXPECT_GT(checked, 200) << "t=" << t;
  }
}

TEST(BlobField, DeterministicAndPeriodic) {
  const BlobParams params;
  const double aggregate = 5005.0;  // lcm of the default periods 5, 7, 11, 13 s
  for (double t : {0.0, 2.5, 17.25}) {
    const BlobField a(t), b(t), later(t + aggregate);
    for (int i = 0; i < BlobParams::kBlobCount; ++i) {
      const BlobField own(t + params.period[static_cast<std::size_t>(i)]);
      // Same t → bit-identical; one period later → the same up to rounding of t itself.
      EXPECT_EQ(a.centre(i), b.centre(i));
      EXPECT_LT(glm::length(own.centre(i) - a.centre(i)), 1e-12);
      EXPECT_LT(glm::length(later.centre(i) - a.centre(i)), 1e-12);
    }
    for (const glm::dvec3& p : probePoints(a)) {
      EXPECT_EQ(a.value(p), b.value(p));
      EXPECT_NEAR(later.value(p), a.value(p), 1e-9);
    }
  }
  // Different periods: the shape does change within the shortest period.
  EXPECT_GT(glm::length(BlobField(1.0).centre(0) - BlobField(1.0).centre(1)), 1e-3);
}

TEST(BlobField, BoundsContainTheSurface) {
  for (double t = 0.0; t < 20.0; t += 0.7) {
    const BlobField field(t);
    const SampledLattice lattice = sampleField(field, 24);
    const int last = lattice.n - 1;
    for (int a = 0; a < lattice.n; ++a)
      for (int b = 0; b < lattice.n; ++b)
        for (float v : {lattice.at(0, a, b), lattice.at(last, a, b), lattice.at(a, 0, b), lattice.at(a, last, b),
                        lattice.at(a, b, 0), lattice.at(a, b, last)})
          ASSERT_GT(v, 0.0f) << "t=" << t;
  }
}

/// With the default parameters blob 3 is then ≥ 2.1 units from the other three, while two blobs
/// join only when closer than 2√(ln(2 / iso) / σ) ≈ 1.18 units (see BlobParams::sigma).
constexpr double kSplitTime = 3.95;

TEST(BlobField, BlobsMergeAndSplit) {
  constexpr int kResolution = 48;
  // t = 0: every path starts at the origin, one merged ball.
  const TriangleMesh merged = meshOnCpu(BlobField(0.0), kResolution);
  EXPECT_EQ(countComponents(merged), 1);
  // Later the blobs drift apart into separate pieces.
  const TriangleMesh split = meshOnCpu(BlobField(kSplitTime), kResolution);
  EXPECT_GE(countComponents(split), 2);
}

TEST(BlobField, MeshesAreClosedOutwardAndOnTheSurface) {
  for (double t : {0.0, 1.1, 2.6, kSplitTime, 7.3}) {
    for (int n : {32, 64}) {
      const BlobField field(t);
      const SampledLattice lattice = sampleField(field, n);
      const TriangleMesh mesh = meshOnCpu(lattice, field);
      ASSERT_FALSE(mesh.triangles.empty());
      for (const auto& [edge, uses] : edgeUses(mesh)) ASSERT_EQ(uses, 2) << "t=" << t << " n=" << n;
      EXPECT_GT(signedVolume(mesh), 0.0);
      // Distance to the isosurface, to first order: |value| / |∇value|.
      for (const glm::vec3& v : mesh.positions) {
        const glm::dvec3 p(v);
        EXPECT_LT(std::abs(field.value(p)) / glm::length(field.gradient(p)), 0.5 * lattice.cellSize)
            << "t=" << t << " n=" << n;
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Lattice sampling

TEST(GridSampler, LayoutIsXFastestWithOnePaddingCell) {
  struct Linear final : ScalarField {
    double value(glm::dvec3 p) const override { return p.x + 2.0 * p.y + 4.0 * p.z; }
    Aabb bounds() const override { return cube(glm::dvec3(0.5, -1.0, 2.0), 0.5); }
  } field;
  const SampledLattice lattice = sampleField(field, 10);
  ASSERT_EQ(lattice.values.size(), 1000u);
  EXPECT_NEAR(lattice.cellSize, 1.0 / 7.0, 1e-12);  // 9 cells span the side plus two padding cells
  EXPECT_NEAR(glm::length(lattice.origin - (glm::dvec3(0.0, -1.5, 1.5) - lattice.cellSize)), 0.0, 1e-6);
  EXPECT_EQ(lattice.index(1, 0, 0), 1u);
  EXPECT_EQ(lattice.index(0, 1, 0), 10u);
  EXPECT_EQ(lattice.index(0, 0, 1), 100u);
  for (int z = 0; z < 10; z += 3)
    for (int y = 0; y < 10; y += 4)
      for (int x = 0; x < 10; ++x)
        EXPECT_NEAR(lattice.at(x, y, z), field.value(lattice.position(x, y, z)), 1e-5);
  EXPECT_THROW(sampleField(field, 3), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------
// CPU reference mesher

TEST(CpuMesher, SphereIsWatertightOutwardAndAccurate) {
  const double r = 0.05;
  const glm::dvec3 c(0.01, -0.02, 0.03);
  const SphereField field(c, r, cube(c, 1.1 * r));
  const SampledLattice lattice = sampleField(field, 64);
  const TriangleMesh mesh = meshOnCpu(lattice, field);
  ASSERT_FALSE(mesh.triangles.empty());
  ASSERT_EQ(mesh.normals.size(), mesh.positions.size());

  for (const auto& [edge, uses] : edgeUses(mesh)) ASSERT_EQ(uses, 2) << edge.first << "-" << edge.second;
  EXPECT_EQ(countComponents(mesh), 1);

  const double exact = 4.0 / 3.0 * std::numbers::pi * r * r * r;
  const double volume = signedVolume(mesh);
  EXPECT_GT(volume, 0.0);
  EXPECT_NEAR(volume, exact, 0.01 * exact);
  RecordProperty("relative_volume_error", std::to_string(volume / exact - 1.0));

  const double h = lattice.cellSize;
  for (const glm::vec3& v : mesh.positions) EXPECT_LT(std::abs(field.value(glm::dvec3(v))), 0.5 * h);
  for (const auto& t : mesh.triangles) {
    const glm::dvec3 n = faceCross(mesh, t);
    // "Zero area": below 1e-6 of a cell face, far under any real triangle at this resolution.
    ASSERT_GT(0.5 * glm::length(n), 1e-6 * h * h);
    // Winding and gradient normals agree: both outward.
    const glm::dvec3 vertexNormals =
        glm::dvec3(mesh.normals[t[0]]) + glm::dvec3(mesh.normals[t[1]]) + glm::dvec3(mesh.normals[t[2]]);
    EXPECT_GT(glm::dot(n, vertexNormals), 0.0);
  }
}

TEST(CpuMesher, SurfaceLeavingTheDomainIsCutOpen) {
  const double r = 0.05;
  // The box covers only part of the sphere: the surface crosses the lattice boundary.
  const SphereField field(glm::dvec3(0.0), r, cube(glm::dvec3(0.03, 0.0, 0.0), 0.6 * r));
  const TriangleMesh mesh = meshOnCpu(field, 32);
  ASSERT_FALSE(mesh.triangles.empty());
  for (const auto& t : mesh.triangles)
    for (std::uint32_t i : t) ASSERT_LT(i, mesh.positions.size());
  for (const glm::vec3& v : mesh.positions) ASSERT_TRUE(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z));
}

TEST(CpuMesher, IsovalueExactlyAtSamples) {
  // Samples within a quarter cell of the sphere are snapped to exactly 0: the mesher must still
  // close the surface with properly wound triangles.
  const double r = 0.05;
  const SphereField field(glm::dvec3(0.0), r, cube(glm::dvec3(0.0), 1.1 * r));
  SampledLattice lattice = sampleField(field, 40);
  int snapped = 0;
  for (float& v : lattice.values)
    if (std::abs(v) < 0.25 * lattice.cellSize) {
      v = 0.0f;
      ++snapped;
    }
  ASSERT_GT(snapped, 0);
  const TriangleMesh mesh = meshOnCpu(lattice, field);
  for (const auto& [edge, uses] : edgeUses(mesh)) ASSERT_EQ(uses, 2);
  const double exact = 4.0 / 3.0 * std::numbers::pi * r * r * r;
  EXPECT_NEAR(signedVolume(mesh), exact, 0.03 * exact);
  for (const auto& t : mesh.triangles)
    EXPECT_GT(0.5 * glm::length(faceCross(mesh, t)), 1e-6 * lattice.cellSize * lattice.cellSize);
}

TEST(CpuMesher, EmptyWhenNoSurface) {
  const SphereField field(glm::dvec3(1.0), 0.01, cube(glm::dvec3(0.0), 0.1));  // sphere outside
  EXPECT_TRUE(meshOnCpu(field, 16).triangles.empty());
}

}  // namespace
}  // namespace tallow::geometry
