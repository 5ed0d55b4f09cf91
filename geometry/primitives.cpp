#include "geometry/primitives.h"

#include <glm/gtc/constants.hpp>

#include <cmath>
#include <stdexcept>
#include <vector>

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

TriangleMesh makeHollowCylinder(double innerRadius, double outerRadius, double height, double bottomThickness,
                                int segments) {
  if (!(innerRadius > 0.0 && innerRadius < outerRadius) || !(bottomThickness > 0.0 && bottomThickness < height) ||
      segments < 3)
    throw std::invalid_argument("makeHollowCylinder: needs 0 < inner radius < outer radius, 0 < bottom < height "
                                "and at least 3 segments");
  // One table of directions, so that every surface puts a rim vertex at bit-identical coordinates.
  std::vector<glm::dvec3> radial(static_cast<std::size_t>(segments));
  for (int s = 0; s < segments; ++s) {
    const double phi = 2.0 * glm::pi<double>() * s / segments;
    radial[static_cast<std::size_t>(s)] = {std::cos(phi), 0.0, -std::sin(phi)};
  }
  TriangleMesh m;
  const auto u = [](std::size_t i) { return static_cast<std::uint32_t>(i); };
  const auto next = [segments](int s) { return (s + 1) % segments; };
  // Ring of `segments` vertices at radius r and height y with the given normals; returns its first index.
  const auto ring = [&](double r, double y, auto&& normal) {
    const std::size_t base = m.positions.size();
    for (int s = 0; s < segments; ++s) {
      const glm::dvec3 d = radial[static_cast<std::size_t>(s)];
      m.positions.emplace_back(glm::dvec3(r * d.x, y, r * d.z));
      m.normals.emplace_back(normal(d));
    }
    return base;
  };
  const auto outward = [](glm::dvec3 d) { return d; };
  const auto inward = [](glm::dvec3 d) { return -d; };
  const auto up = [](glm::dvec3) { return glm::dvec3(0.0, 1.0, 0.0); };
  const auto down = [](glm::dvec3) { return glm::dvec3(0.0, -1.0, 0.0); };
  // Walls: the tangent dp/dφ × (+y) is the outward radial direction, so (a, b, c) with a → b
  // along increasing φ and c above b winds outward.
  const auto wall = [&](double r, double y0, double y1, bool facingOut) {
    const std::size_t lo = facingOut ? ring(r, y0, outward) : ring(r, y0, inward);
    const std::size_t hi = facingOut ? ring(r, y1, outward) : ring(r, y1, inward);
    for (int s = 0; s < segments; ++s) {
      const std::uint32_t a = u(lo + s), b = u(lo + next(s)), c = u(hi + next(s)), d = u(hi + s);
      if (facingOut) {
        m.triangles.push_back({a, b, c});
        m.triangles.push_back({a, c, d});
      } else {
        m.triangles.push_back({a, c, b});
        m.triangles.push_back({a, d, c});
      }
    }
  };
  wall(outerRadius, 0.0, height, true);
  wall(innerRadius, bottomThickness, height, false);
  // Top annulus, normal +y: outer(s) → outer(s+1) → inner(s+1) winds counter-clockwise from above.
  {
    const std::size_t outer = ring(outerRadius, height, up), inner = ring(innerRadius, height, up);
    for (int s = 0; s < segments; ++s) {
      m.triangles.push_back({u(outer + s), u(outer + next(s)), u(inner + next(s))});
      m.triangles.push_back({u(outer + s), u(inner + next(s)), u(inner + s)});
    }
  }
  // Discs as fans about a centre vertex: the cavity's floor facing up, the bottom facing down.
  const auto disc = [&](double r, double y, bool facingUp) {
    const std::size_t rim = facingUp ? ring(r, y, up) : ring(r, y, down);
    const auto centre = u(m.positions.size());
    m.positions.emplace_back(0.0f, static_cast<float>(y), 0.0f);
    m.normals.emplace_back(0.0f, facingUp ? 1.0f : -1.0f, 0.0f);
    for (int s = 0; s < segments; ++s) {
      if (facingUp)
        m.triangles.push_back({centre, u(rim + s), u(rim + next(s))});
      else
        m.triangles.push_back({centre, u(rim + next(s)), u(rim + s)});
    }
  };
  disc(innerRadius, bottomThickness, true);
  disc(outerRadius, 0.0, false);
  return m;
}

}  // namespace tallow::geometry
