#include "geometry/scalar_field.h"

#include <algorithm>

namespace tallow::geometry {

ScalarField::~ScalarField() = default;

glm::dvec3 ScalarField::gradient(glm::dvec3 p) const {
  const Aabb box = bounds();
  const glm::dvec3 size = box.empty() ? glm::dvec3(1.0) : glm::dvec3(box.size());
  const double extent = std::max({size.x, size.y, size.z, 1e-6});
  return centralDifferenceGradient(p, kGradientStepRelative * extent);
}

glm::dvec3 ScalarField::centralDifferenceGradient(glm::dvec3 p, double h) const {
  glm::dvec3 g;
  for (int axis = 0; axis < 3; ++axis) {
    glm::dvec3 d(0.0);
    d[axis] = h;
    g[axis] = (value(p + d) - value(p - d)) / (2.0 * h);
  }
  return g;
}

}  // namespace tallow::geometry
