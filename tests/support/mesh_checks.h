#pragma once
// Quality measures of triangle meshes shared by the geometry tests: enclosed volume, area, face
// normals, edge use (watertightness), connected components and the Hausdorff distance between two
// meshes (point-to-triangle distances through a uniform bucket grid).
#include <glm/glm.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numeric>
#include <utility>
#include <vector>

#include "geometry/analytic_fields.h"
#include "geometry/mesh_distance.h"
#include "geometry/scalar_field.h"
#include "geometry/triangle_mesh.h"

namespace tallow::test {

/// Signed enclosed volume by the divergence theorem: Σ a·(b×c) / 6 (> 0 for outward winding).
inline double signedVolume(const geometry::TriangleMesh& mesh) {
  double v = 0.0;
  for (const auto& t : mesh.triangles)
    v += glm::dot(glm::dvec3(mesh.positions[t[0]]),
                  glm::cross(glm::dvec3(mesh.positions[t[1]]), glm::dvec3(mesh.positions[t[2]])));
  return v / 6.0;
}

/// (b − a) × (c − a): the face normal by the winding, length twice the area.
inline glm::dvec3 faceCross(const geometry::TriangleMesh& mesh, const std::array<std::uint32_t, 3>& t) {
  const glm::dvec3 a(mesh.positions[t[0]]), b(mesh.positions[t[1]]), c(mesh.positions[t[2]]);
  return glm::cross(b - a, c - a);
}

/// How many triangles use each undirected edge.
inline std::map<std::pair<std::uint32_t, std::uint32_t>, int> edgeUses(const geometry::TriangleMesh& mesh) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
  for (const auto& t : mesh.triangles)
    for (std::size_t i = 0; i < 3; ++i) ++uses[std::minmax(t[i], t[(i + 1) % 3])];
  return uses;
}

/// Number of undirected edges not used by exactly two triangles (0 for a watertight mesh).
inline int badEdges(const geometry::TriangleMesh& mesh) {
  int bad = 0;
  for (const auto& [edge, n] : edgeUses(mesh)) bad += n == 2 ? 0 : 1;
  return bad;
}

/// Connected components of the triangles (sharing a vertex joins them), by union-find.
inline int countComponents(const geometry::TriangleMesh& mesh) {
  std::vector<std::uint32_t> parent(mesh.positions.size());
  std::iota(parent.begin(), parent.end(), 0u);
  auto find = [&](std::uint32_t v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  std::vector<bool> used(mesh.positions.size(), false);
  for (const auto& t : mesh.triangles) {
    for (std::uint32_t v : t) used[v] = true;
    parent[find(t[1])] = find(t[0]);
    parent[find(t[2])] = find(t[0]);
  }
  int count = 0;
  for (std::uint32_t v = 0; v < parent.size(); ++v) count += (used[v] && find(v) == v) ? 1 : 0;
  return count;
}

/// Total area of the triangles.
inline double surfaceArea(const geometry::TriangleMesh& mesh) {
  double area = 0.0;
  for (const auto& t : mesh.triangles) area += 0.5 * glm::length(faceCross(mesh, t));
  return area;
}

using geometry::pointTriangleDistance;
using geometry::TriangleGrid;

/// Largest distance from a vertex used by `from`'s triangles to the surface of `to` (capped at
/// `cap`): the one-sided Hausdorff distance with vertices standing for the surface of `from`.
inline double directedHausdorff(const geometry::TriangleMesh& from, const geometry::TriangleMesh& to, double bucketSize,
                                double cap) {
  const TriangleGrid grid(to, bucketSize);
  std::vector<bool> used(from.positions.size(), false);
  for (const auto& t : from.triangles)
    for (std::uint32_t v : t) used[v] = true;
  double worst = 0.0;
  for (std::size_t v = 0; v < from.positions.size(); ++v)
    if (used[v]) worst = std::max(worst, grid.distance(glm::dvec3(from.positions[v]), cap));
  return worst;
}

/// Symmetric Hausdorff distance between two meshes (vertex-to-surface both ways), capped at `cap`.
inline double hausdorffDistance(const geometry::TriangleMesh& a, const geometry::TriangleMesh& b, double bucketSize,
                                double cap) {
  return std::max(directedHausdorff(a, b, bucketSize, cap), directedHausdorff(b, a, bucketSize, cap));
}

/// The exact sphere (geometry/analytic_fields.h), under the name the tests have always used.
using SphereField = geometry::SphereField;

}  // namespace tallow::test
