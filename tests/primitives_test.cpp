// The built-in shapes of geometry/primitives.h; here the hollow cylinder of the candle-holder
// preset: closed (watertight once its rim vertices are welded), wound outward (signed volume equal
// to the analytic volume of the N-gon solid), with vertex normals that agree with the winding.
#include <gtest/gtest.h>

#include <glm/gtc/constants.hpp>

#include <cmath>
#include <map>
#include <stdexcept>
#include <tuple>

#include "geometry/primitives.h"
#include "support/mesh_checks.h"

namespace tallow {
namespace {

/// The mesh with vertices at bit-identical positions merged (normals dropped): creases duplicate
/// vertices for their normals, and watertightness is about the surface, not the normals.
geometry::TriangleMesh weldByPosition(const geometry::TriangleMesh& mesh) {
  geometry::TriangleMesh welded;
  std::map<std::tuple<float, float, float>, std::uint32_t> index;
  std::vector<std::uint32_t> remap(mesh.positions.size());
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    const glm::vec3 p = mesh.positions[v];
    const auto [it, added] = index.emplace(std::make_tuple(p.x, p.y, p.z), static_cast<std::uint32_t>(welded.positions.size()));
    if (added) welded.positions.push_back(p);
    remap[v] = it->second;
  }
  for (const auto& t : mesh.triangles) welded.triangles.push_back({remap[t[0]], remap[t[1]], remap[t[2]]});
  return welded;
}

/// Area of the regular n-gon inscribed in a circle of radius r: the shape's exact cross-section.
double ngonArea(double r, int n) { return 0.5 * n * r * r * std::sin(2.0 * glm::pi<double>() / n); }

struct CupCase {
  double inner, outer, height, bottom;
  int segments;
};

class HollowCylinder : public ::testing::TestWithParam<CupCase> {};

TEST_P(HollowCylinder, IsWatertightOnceWelded) {
  const CupCase c = GetParam();
  const geometry::TriangleMesh mesh = geometry::makeHollowCylinder(c.inner, c.outer, c.height, c.bottom, c.segments);
  const geometry::TriangleMesh welded = weldByPosition(mesh);
  EXPECT_EQ(test::badEdges(welded), 0);
  EXPECT_EQ(test::countComponents(welded), 1);
  // Euler characteristic of a closed genus-0 surface (the cavity is a dent, not a hole): V − E + F = 2.
  const auto edges = static_cast<long>(test::edgeUses(welded).size());
  EXPECT_EQ(static_cast<long>(welded.positions.size()) - edges + static_cast<long>(welded.triangles.size()), 2);
  // Welded vertices: the outer circle at the bottom and the top, the inner circle at the top and at
  // the cavity's floor, and the centres of the two discs.
  EXPECT_EQ(welded.positions.size(), static_cast<std::size_t>(4 * c.segments + 2));
}

TEST_P(HollowCylinder, WindsOutwardWithTheVolumeOfTheNgonSolid) {
  const CupCase c = GetParam();
  const geometry::TriangleMesh mesh = geometry::makeHollowCylinder(c.inner, c.outer, c.height, c.bottom, c.segments);
  // The solid is the outer N-gon prism minus the cavity's N-gon prism above the bottom.
  const double exact = ngonArea(c.outer, c.segments) * c.height - ngonArea(c.inner, c.segments) * (c.height - c.bottom);
  const double volume = test::signedVolume(mesh);
  EXPECT_GT(volume, 0.0);
  EXPECT_NEAR(volume, exact, 1e-5 * exact);  // float vertex coordinates
  // Against the round shell π(R² − r²)h + πr²·bottom, the only difference is the chord error of
  // the polygons: each circle loses πr² − A_N(r) of its area.
  const double round = glm::pi<double>() * (c.outer * c.outer - c.inner * c.inner) * c.height +
                       glm::pi<double>() * c.inner * c.inner * c.bottom;
  const double chordLoss = (glm::pi<double>() * c.outer * c.outer - ngonArea(c.outer, c.segments)) * c.height;
  EXPECT_LE(std::abs(volume - round), chordLoss + 1e-5 * round);
  // Walls (perimeter of the N-gon × height), top annulus, cavity floor, bottom disc.
  const double area = 2.0 * c.segments * std::sin(glm::pi<double>() / c.segments) *
                          (c.outer * c.height + c.inner * (c.height - c.bottom)) +
                      (ngonArea(c.outer, c.segments) - ngonArea(c.inner, c.segments)) + ngonArea(c.inner, c.segments) +
                      ngonArea(c.outer, c.segments);
  EXPECT_NEAR(test::surfaceArea(mesh), area, 1e-5 * area);
}

TEST_P(HollowCylinder, NormalsAreUnitAndAgreeWithTheWinding) {
  const CupCase c = GetParam();
  const geometry::TriangleMesh mesh = geometry::makeHollowCylinder(c.inner, c.outer, c.height, c.bottom, c.segments);
  ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
  for (const glm::vec3& n : mesh.normals) EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
  // Each vertex normal points to the side its triangles face: within the half-angle of a segment
  // of the face normal (walls are smooth-shaded across the segments), exactly along it on the caps.
  const double minCos = std::cos(glm::pi<double>() / c.segments) - 1e-5;
  int wrong = 0;
  for (const auto& t : mesh.triangles) {
    const glm::dvec3 f = glm::normalize(test::faceCross(mesh, t));
    for (std::uint32_t v : t) wrong += glm::dot(f, glm::dvec3(mesh.normals[v])) >= minCos ? 0 : 1;
  }
  EXPECT_EQ(wrong, 0);
  // Inner wall faces the axis, outer wall away from it; the cavity floor faces up.
  int intoCavity = 0;
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    const glm::dvec3 p(mesh.positions[v]), n(mesh.normals[v]);
    const double r = std::hypot(p.x, p.z);
    if (std::abs(r - c.inner) < 1e-6 && std::abs(n.y) < 1e-6) {
      EXPECT_LT(n.x * p.x + n.z * p.z, 0.0);
      ++intoCavity;
    }
  }
  EXPECT_EQ(intoCavity, 2 * c.segments);
}

TEST_P(HollowCylinder, StandsOnItsBottomCentreWithinItsRadius) {
  const CupCase c = GetParam();
  const geometry::TriangleMesh mesh = geometry::makeHollowCylinder(c.inner, c.outer, c.height, c.bottom, c.segments);
  const geometry::Aabb box = mesh.bounds();
  EXPECT_NEAR(box.min.y, 0.0f, 1e-7f);
  EXPECT_NEAR(box.max.y, c.height, 1e-6 * c.height);
  EXPECT_NEAR(box.max.x, c.outer, 1e-6 * c.outer);  // a vertex at angle 0
  EXPECT_GE(box.min.x, -c.outer * (1 + 1e-6));
  for (const glm::vec3& p : mesh.positions) {
    const double r = std::hypot(double(p.x), double(p.z));
    EXPECT_LE(r, c.outer * (1 + 1e-6));
    // Nothing inside the open cavity: a vertex with r < inner lies on its floor, the bottom or the top.
    if (r < c.inner * (1 - 1e-6)) {
      EXPECT_TRUE(std::abs(p.y - c.bottom) < 1e-6 || std::abs(p.y) < 1e-7);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Shapes, HollowCylinder,
                         ::testing::Values(CupCase{0.03, 0.04, 0.08, 0.01, 128},  // the candle-holder preset
                                           CupCase{0.5, 1.0, 2.0, 0.25, 3},       // coarsest: a triangle
                                           CupCase{0.9, 1.0, 0.3, 0.1, 17}));

TEST(HollowCylinderArguments, AreChecked) {
  EXPECT_THROW(geometry::makeHollowCylinder(0.04, 0.03, 0.08, 0.01, 32), std::invalid_argument);
  EXPECT_THROW(geometry::makeHollowCylinder(0.0, 0.03, 0.08, 0.01, 32), std::invalid_argument);
  EXPECT_THROW(geometry::makeHollowCylinder(0.02, 0.03, 0.08, 0.08, 32), std::invalid_argument);
  EXPECT_THROW(geometry::makeHollowCylinder(0.02, 0.03, 0.08, 0.01, 2), std::invalid_argument);
}

}  // namespace
}  // namespace tallow
