#pragma once
// An indexed triangle mesh in object space, as read from a file or generated.
#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <limits>
#include <vector>

namespace tallow::geometry {

struct Aabb {
  glm::vec3 min{std::numeric_limits<float>::max()};
  glm::vec3 max{-std::numeric_limits<float>::max()};
  void extend(const glm::vec3& p) { min = glm::min(min, p); max = glm::max(max, p); }
  bool empty() const { return min.x > max.x; }
  glm::vec3 size() const { return max - min; }
  glm::vec3 centre() const { return 0.5f * (min + max); }
};

struct TriangleMesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  ///< per vertex, unit length; empty until computed or read
  std::vector<std::array<std::uint32_t, 3>> triangles;  ///< counter-clockwise seen from outside

  Aabb bounds() const;  ///< over the vertices that triangles use
};

/// Area-weighted vertex normals from the faces (replaces any stored normals). Vertices used by no
/// face, or only by degenerate ones, get (0, 1, 0) so that no NaN reaches a shader.
void computeVertexNormals(TriangleMesh& mesh);

}  // namespace tallow::geometry
