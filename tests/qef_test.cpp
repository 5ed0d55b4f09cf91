// The vertex placement of dual contouring's QEF (shaders/dual_contouring/qef.glsl), compiled as
// C++: the same lines the vertex pass runs. Expected values come from the closed-form minimum of
// the probabilistic quadric worked out by hand for planes along the cell's axes (see each test).
#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include <algorithm>
#include <initializer_list>
#include <utility>
#include <vector>

#include "gpu/glsl_shared.h"

namespace tallow::glsl {
#include "shaders/dual_contouring/qef.glsl"
}  // namespace tallow::glsl

namespace tallow {
namespace {

using glsl::DC_CELL_MARGIN;
using glsl::DC_QEF_SIGMA_N;
using glsl::DcQuadric;

DcQuadric quadricOf(const std::vector<std::pair<glm::vec3, glm::vec3>>& planes) {
  DcQuadric q = glsl::dcQuadricEmpty();
  for (const auto& [p, n] : planes) q = glsl::dcQuadricAdd(q, p, n);
  return q;
}

/// Σ over the planes of the probabilistic quadric's varying part, (x − p)ᵀ(n nᵀ + σ² I)(x − p).
float quadricValue(const std::vector<std::pair<glm::vec3, glm::vec3>>& planes, glm::vec3 x, float sigma) {
  float sum = 0.0f;
  for (const auto& [p, n] : planes) {
    const glm::vec3 d = x - p;
    sum += glm::dot(n, d) * glm::dot(n, d) + sigma * sigma * glm::dot(d, d);
  }
  return sum;
}

glm::vec3 meanOf(const std::vector<std::pair<glm::vec3, glm::vec3>>& planes) {
  glm::vec3 m(0.0f);
  for (const auto& pn : planes) m += pn.first;
  return m / static_cast<float>(planes.size());
}

// A corner of three faces along the axes at c = (0.6, 0.35, 0.7): two crossings on each face, each
// on an edge of the cell. With A = Σ n nᵀ = diag(k_x, k_y, k_z) (k_j crossings on the face
// normal to axis j) and Σ n nᵀ (p − m) = k_j (c_j − m_j) along axis j, the minimum is, per axis,
//   x_j = m_j + k_j (c_j − m_j) / (k_j + k σ²)
// — the corner, pulled toward the mass point by the fraction k σ² / (k_j + k σ²).
TEST(DcQef, CornerOfThreeFacesIsFoundUpToThePullTowardTheMassPoint) {
  const glm::vec3 c(0.6f, 0.35f, 0.7f);
  const std::vector<std::pair<glm::vec3, glm::vec3>> planes{
      {{c.x, 0.0f, 1.0f}, {1, 0, 0}}, {{c.x, 1.0f, 0.0f}, {1, 0, 0}},
      {{0.0f, c.y, 0.0f}, {0, 1, 0}}, {{1.0f, c.y, 1.0f}, {0, 1, 0}},
      {{0.0f, 1.0f, c.z}, {0, 0, 1}}, {{1.0f, 0.0f, c.z}, {0, 0, 1}}};
  const DcQuadric q = quadricOf(planes);
  const glm::vec3 m = meanOf(planes);
  EXPECT_LT(glm::length(glsl::dcQuadricMassPoint(q) - m), 1e-6f);
  const float k = 6.0f, kj = 2.0f, s2 = DC_QEF_SIGMA_N * DC_QEF_SIGMA_N;
  const glm::vec3 expected = m + kj * (c - m) / (kj + k * s2);
  const glm::vec3 x = glsl::dcQuadricMinimum(q, DC_QEF_SIGMA_N);
  for (int j = 0; j < 3; ++j) EXPECT_NEAR(x[j], expected[j], 1e-5f) << "axis " << j;
  // The mass point is far from the corner; the QEF's vertex within 3% of that distance of it.
  EXPECT_GT(glm::length(m - c), 0.15f);
  EXPECT_LT(glm::length(x - c), 0.03f * glm::length(m - c));
  // Without the pull (σ → 0) the planes' intersection itself.
  const glm::vec3 exact = glsl::dcQuadricMinimum(q, 1e-4f);
  EXPECT_LT(glm::length(exact - c), 1e-5f);
  // Inside the cell already: kept as it is.
  EXPECT_EQ(glsl::dcQuadricVertex(q, DC_QEF_SIGMA_N), x);
}

// A flat patch: all normals alike. Σ n nᵀ (p_i − m) = n nᵀ Σ (p_i − m) = 0, so x = m for any σ, up
// to float rounding (≈ 1e-7) magnified by the condition number of Σ n nᵀ + k σ² I, 1 + 1/σ² ≤ 101.
TEST(DcQef, FlatPatchKeepsTheMassPoint) {
  const glm::vec3 n = glm::normalize(glm::vec3(0.3f, 0.9f, -0.2f));
  std::vector<std::pair<glm::vec3, glm::vec3>> planes;
  for (const glm::vec3& p : {glm::vec3(0.1f, 0.4f, 0.0f), glm::vec3(1.0f, 0.3f, 0.2f), glm::vec3(0.7f, 0.5f, 1.0f),
                             glm::vec3(0.0f, 0.45f, 0.8f)})
    planes.emplace_back(p, n);
  const DcQuadric q = quadricOf(planes);
  for (float sigma : {DC_QEF_SIGMA_N, 1.0f})
    EXPECT_LT(glm::length(glsl::dcQuadricMinimum(q, sigma) - meanOf(planes)), 2e-5f) << "sigma " << sigma;
}

// A sharp edge along z: faces x = 0.3 and y = 0.8 (two crossings each). Across the edge the same
// per-axis formula holds (k_x = k_y = 2 of k = 4); along it the planes say nothing and the vertex
// keeps the mass point's z.
TEST(DcQef, EdgeOfTwoFacesIsFoundAcrossAndKeepsTheMassPointAlong) {
  const std::vector<std::pair<glm::vec3, glm::vec3>> planes{{{0.3f, 0.0f, 0.2f}, {1, 0, 0}},
                                                            {{0.3f, 1.0f, 0.9f}, {1, 0, 0}},
                                                            {{1.0f, 0.8f, 0.0f}, {0, 1, 0}},
                                                            {{0.0f, 0.8f, 1.0f}, {0, 1, 0}}};
  const DcQuadric q = quadricOf(planes);
  const glm::vec3 m = meanOf(planes), x = glsl::dcQuadricMinimum(q, DC_QEF_SIGMA_N);
  const float pull = 2.0f / (2.0f + 4.0f * DC_QEF_SIGMA_N * DC_QEF_SIGMA_N);
  EXPECT_NEAR(x.x, m.x + pull * (0.3f - m.x), 1e-5f);
  EXPECT_NEAR(x.y, m.y + pull * (0.8f - m.y), 1e-5f);
  EXPECT_NEAR(x.z, m.z, 1e-6f);
}

// A crossing where the field has no gradient (n = 0) only pulls toward itself: with a single such
// crossing the vertex is that crossing.
TEST(DcQef, CrossingWithoutNormalPullsOnlyTowardItself) {
  const glm::vec3 p(0.25f, 0.5f, 1.0f);
  const DcQuadric q = glsl::dcQuadricAdd(glsl::dcQuadricEmpty(), p, glm::vec3(0.0f));
  EXPECT_LT(glm::length(glsl::dcQuadricMinimum(q, DC_QEF_SIGMA_N) - p), 1e-6f);
}

// Two faces meeting at a shallow angle whose intersection line lies far outside the cell (a
// sliver): the unconstrained minimum leaves the cell, the vertex stops where the segment from the
// mass point toward it leaves the cell, and is no worse on the quadric than the mass point.
TEST(DcQef, MinimumOutsideTheCellIsBroughtBackAlongTheSegmentFromTheMassPoint) {
  const glm::vec3 n1 = glm::normalize(glm::vec3(0.0f, 1.0f, 0.25f)), n2 = glm::normalize(glm::vec3(0.0f, 1.0f, -0.25f));
  // Plane 1 through (0, 0.5, 0): y = 0.5 − z/4; plane 2 through (0, 0.15, 1): y = 0.15 + (z − 1)/4.
  // They meet at z = 1.2, y = 0.2, beyond the cell's face z = 1; the crossings lie on the faces
  // z = 0 and z = 1.
  auto onPlane = [](glm::vec3 n, glm::vec3 o, float x, float z) {
    const float y = o.y - (n.z * (z - o.z)) / n.y;
    return glm::vec3(x, y, z);
  };
  const glm::vec3 o1(0.0f, 0.5f, 0.0f), o2(0.0f, 0.15f, 1.0f);
  const std::vector<std::pair<glm::vec3, glm::vec3>> planes{
      {onPlane(n1, o1, 0.0f, 0.0f), n1}, {onPlane(n1, o1, 1.0f, 0.0f), n1},
      {onPlane(n2, o2, 0.0f, 1.0f), n2}, {onPlane(n2, o2, 1.0f, 1.0f), n2}};
  const DcQuadric q = quadricOf(planes);
  const glm::vec3 m = glsl::dcQuadricMassPoint(q);
  const glm::vec3 x = glsl::dcQuadricMinimum(q, DC_QEF_SIGMA_N);
  ASSERT_TRUE(x.y < 0.0f || x.y > 1.0f || x.z < 0.0f || x.z > 1.0f) << "the test needs a minimum outside the cell";
  const glm::vec3 v = glsl::dcQuadricVertex(q, DC_QEF_SIGMA_N);
  for (int j = 0; j < 3; ++j) {
    EXPECT_GE(v[j], DC_CELL_MARGIN);
    EXPECT_LE(v[j], 1.0f - DC_CELL_MARGIN);
  }
  // On the segment m → x, and DC_CELL_MARGIN inside the cell's boundary.
  const glm::vec3 d = x - m;
  const float t = glm::dot(v - m, d) / glm::dot(d, d);
  EXPECT_GT(t, 0.0f);
  EXPECT_LT(t, 1.0f);
  EXPECT_LT(glm::length(m + t * d - v), 1e-5f);
  EXPECT_NEAR(std::min({v.y, 1.0f - v.y, v.z, 1.0f - v.z}), DC_CELL_MARGIN, 1e-6f);
  EXPECT_LT(quadricValue(planes, v, DC_QEF_SIGMA_N), quadricValue(planes, m, DC_QEF_SIGMA_N));
}

// Neighbouring cells' vertices never meet: whatever the minimum and the mass point (on a face, as
// when every crossing lies on it), the vertex stays DC_CELL_MARGIN inside, so the vertices of two
// cells sharing a face are at least twice that apart across it.
TEST(DcQef, VerticesStayAMarginInsideTheirCell) {
  const glm::vec3 onFace(0.3f, 1.0f, 0.6f), outside(0.5f, 1.7f, 0.4f), inside(0.4f, 0.5f, 0.5f);
  for (const auto& [m, x] : {std::pair{onFace, outside}, std::pair{onFace, onFace}, std::pair{inside, outside},
                             std::pair{glm::vec3(0.0f), glm::vec3(-1.0f, 2.0f, 0.5f)}}) {
    const glm::vec3 v = glsl::dcKeepInCell(m, x);
    for (int j = 0; j < 3; ++j) {
      EXPECT_GE(v[j], DC_CELL_MARGIN) << j;
      EXPECT_LE(v[j], 1.0f - DC_CELL_MARGIN) << j;
    }
  }
  // A minimum inside the margin box is kept as it is.
  EXPECT_EQ(glsl::dcKeepInCell(inside, glm::vec3(0.2f, 0.7f, 0.9f)), glm::vec3(0.2f, 0.7f, 0.9f));
}

// The lattice derivative: central on smooth samples (exact for a quadratic), one-sided away from a
// crease. f = m on one side of m = 0.3 and 3m − 0.6 on the other: at m = 0 the field's slope is 1;
// the central difference (2.4 + 1) / 2 = 1.7 reaches across the crease, the backward one does not.
TEST(DcQef, LatticeDerivativeIsCentralOnSmoothSamplesAndOneSidedAtACrease) {
  auto quadratic = [](float m) { return 0.3f * m * m - 0.7f * m + 2.0f; };  // derivative at 0: −0.7
  EXPECT_NEAR(glsl::dcLatticeDerivative(quadratic(-2), quadratic(-1), quadratic(0), quadratic(1), quadratic(2)), -0.7f,
              1e-6f);
  auto crease = [](float m) { return m <= 0.3f ? m : 3.0f * m - 0.6f; };
  EXPECT_NEAR(glsl::dcLatticeDerivative(crease(-2), crease(-1), crease(0), crease(1), crease(2)), 1.0f, 1e-6f);
  // Mirrored: the crease on the other side, the forward difference.
  auto mirrored = [&](float m) { return crease(-m); };
  EXPECT_NEAR(glsl::dcLatticeDerivative(mirrored(-2), mirrored(-1), mirrored(0), mirrored(1), mirrored(2)), -1.0f,
              1e-6f);
  // A plane: every second difference 0, central.
  EXPECT_NEAR(glsl::dcLatticeDerivative(-4.0f, -2.0f, 0.0f, 2.0f, 4.0f), 2.0f, 1e-6f);
}

// The lattice's own surface: for a cell whose corner values are a plane's field f = x − 0.3 the
// trilinear interpolant is that plane, and the first-order distance is exact. A vertex 0.65 from it
// is brought back along the segment from the mass point to where it is 0.5 away (x = 0.8), to the
// bisection's 1/256 of the 0.65-long segment; one within 0.5 stays.
TEST(DcQef, VertexIsKeptWithinHalfACellOfTheLatticesSurface) {
  float v[8];
  for (int i = 0; i < 8; ++i) v[i] = static_cast<float>(i & 1) - 0.3f;
  EXPECT_NEAR(glsl::dcTrilinearDistance(v, glm::vec3(0.9f, 0.2f, 0.7f)), 0.6f, 1e-6f);
  const glm::vec3 m(0.3f, 0.5f, 0.5f);
  const glm::vec3 limited = glsl::dcLimitToLattice(v, m, glm::vec3(0.95f, 0.5f, 0.5f));
  EXPECT_LE(limited.x, 0.8f + 1e-6f);
  EXPECT_GE(limited.x, 0.8f - 0.65f / 256.0f - 1e-6f);
  EXPECT_FLOAT_EQ(limited.y, 0.5f);
  const glm::vec3 near(0.75f, 0.1f, 0.9f);
  EXPECT_EQ(glsl::dcLimitToLattice(v, m, near), near);
}

}  // namespace
}  // namespace tallow
