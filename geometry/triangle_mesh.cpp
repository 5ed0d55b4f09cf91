#include "geometry/triangle_mesh.h"

#include <cmath>

namespace tallow::geometry {

Aabb TriangleMesh::bounds() const {
  Aabb box;
  for (const auto& t : triangles)
    for (std::uint32_t i : t) box.extend(positions[i]);
  return box;
}

void computeVertexNormals(TriangleMesh& mesh) {
  std::vector<glm::dvec3> sum(mesh.positions.size(), glm::dvec3(0.0));
  for (const auto& t : mesh.triangles) {
    const glm::dvec3 a(mesh.positions[t[0]]), b(mesh.positions[t[1]]), c(mesh.positions[t[2]]);
    const glm::dvec3 n = glm::cross(b - a, c - a);  // length = 2 × area: area weighting for free
    for (std::uint32_t i : t) sum[i] += n;
  }
  mesh.normals.resize(mesh.positions.size());
  for (std::size_t i = 0; i < sum.size(); ++i) {
    const double len = glm::length(sum[i]);
    mesh.normals[i] = (len > 0.0 && std::isfinite(len)) ? glm::vec3(sum[i] / len) : glm::vec3(0, 1, 0);
  }
}

}  // namespace tallow::geometry
