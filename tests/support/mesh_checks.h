#pragma once
// Quality measures of triangle meshes shared by the geometry tests: enclosed volume, face normals,
// edge use (watertightness) and connected components.
#include <glm/glm.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <numeric>
#include <utility>
#include <vector>

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

/// value = ‖p − centre‖ − r: the exact case, a true signed distance, so |value| is the distance to
/// the surface. Bounds: the given box, or a 20% margin around the sphere.
class SphereField final : public geometry::ScalarField {
 public:
  SphereField(glm::dvec3 centre, double radius) : SphereField(centre, radius, margin(centre, radius)) {}
  SphereField(glm::dvec3 centre, double radius, geometry::Aabb box) : centre_(centre), radius_(radius), box_(box) {}
  double value(glm::dvec3 p) const override { return glm::length(p - centre_) - radius_; }
  glm::dvec3 gradient(glm::dvec3 p) const override { return glm::normalize(p - centre_); }
  geometry::Aabb bounds() const override { return box_; }

 private:
  static geometry::Aabb margin(glm::dvec3 centre, double radius) {
    geometry::Aabb box;
    box.extend(glm::vec3(centre - 1.2 * radius));
    box.extend(glm::vec3(centre + 1.2 * radius));
    return box;
  }
  glm::dvec3 centre_;
  double radius_;
  geometry::Aabb box_;
};

}  // namespace tallow::test
