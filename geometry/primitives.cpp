#include "geometry/primitives.h"

#include <glm/gtc/constants.hpp>

#include <cmath>

namespace tallow::geometry {

TriangleMesh makeSphere(int rings, int segments) {
  TriangleMesh m;
  for (int r = 0; r <= rings; ++r) {
    const double theta = glm::pi<double>() * r / rings;
    for (int s = 0; s <= segments; ++s) {
      const double phi = 2.0 * glm::pi<double>() * s / segments;
      const glm::dvec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi));
      m.positions.emplace_back(n);
      m.normals.emplace_back(n);
    }
  }
  const auto idx = [segments](int r, int s) { return static_cast<std::uint32_t>(r * (segments + 1) + s); };
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      // Counter-clockwise seen from outside; skip the degenerate triangles at the poles.
      if (r != 0) m.triangles.push_back({idx(r, s), idx(r + 1, s), idx(r, s + 1)});
      if (r != rings - 1) m.triangles.push_back({idx(r, s + 1), idx(r + 1, s), idx(r + 1, s + 1)});
    }
  return m;
}

TriangleMesh makePlane() {
  TriangleMesh m;
  m.positions = {{-0.5f, 0, -0.5f}, {-0.5f, 0, 0.5f}, {0.5f, 0, 0.5f}, {0.5f, 0, -0.5f}};
  m.normals.assign(4, glm::vec3(0, 1, 0));
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

TriangleMesh makeBox() {
  TriangleMesh m;
  for (int axis = 0; axis < 3; ++axis)
    for (int sign = -1; sign <= 1; sign += 2) {
      glm::vec3 n(0.0f);
      n[axis] = static_cast<float>(sign);
      // Two tangents with t × b = n so that the quad winds counter-clockwise seen from outside.
      glm::vec3 t(0.0f);
      t[(axis + 1) % 3] = 1.0f;
      const glm::vec3 b = glm::cross(n, t);
      const auto base = static_cast<std::uint32_t>(m.positions.size());
      const glm::vec3 c = 0.5f * n;
      m.positions.push_back(c - 0.5f * t - 0.5f * b);
      m.positions.push_back(c + 0.5f * t - 0.5f * b);
      m.positions.push_back(c + 0.5f * t + 0.5f * b);
      m.positions.push_back(c - 0.5f * t + 0.5f * b);
      for (int i = 0; i < 4; ++i) m.normals.push_back(n);
      m.triangles.push_back({base, base + 1, base + 2});
      m.triangles.push_back({base, base + 2, base + 3});
    }
  return m;
}

}  // namespace tallow::geometry
