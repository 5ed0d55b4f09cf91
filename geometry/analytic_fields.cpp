#include "geometry/analytic_fields.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace tallow::geometry {

namespace {

Aabb withMargin(const std::vector<glm::dvec3>& points, double margin) {
  glm::dvec3 lo(points.front()), hi(points.front());
  for (const glm::dvec3& p : points) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  const glm::dvec3 pad = margin * (hi - lo);
  Aabb box;
  box.extend(glm::vec3(lo - pad));
  box.extend(glm::vec3(hi + pad));
  return box;
}

/// Samples from −h to h about `spacing` apart, both ends included.
std::vector<double> span(double h, double spacing) {
  const int steps = std::max(1, static_cast<int>(std::ceil(2.0 * h / spacing)));
  std::vector<double> out(static_cast<std::size_t>(steps) + 1);
  for (int i = 0; i <= steps; ++i) out[static_cast<std::size_t>(i)] = -h + 2.0 * h * i / steps;
  return out;
}

}  // namespace

SphereField::SphereField(glm::dvec3 centre, double radius)
    : SphereField(centre, radius, withMargin({centre - radius, centre + radius}, 0.1)) {}
SphereField::SphereField(glm::dvec3 centre, double radius, Aabb box) : centre_(centre), radius_(radius), box_(box) {}
double SphereField::value(glm::dvec3 p) const { return glm::length(p - centre_) - radius_; }
glm::dvec3 SphereField::gradient(glm::dvec3 p) const { return glm::normalize(p - centre_); }

std::vector<glm::dvec3> SphereField::surfaceSamples(double spacing) const {
  // Fibonacci lattice: z uniform in (−1, 1), longitude advancing by the golden angle (equal areas).
  const auto count = static_cast<int>(std::ceil(4.0 * std::numbers::pi * radius_ * radius_ / (spacing * spacing)));
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  std::vector<glm::dvec3> out;
  out.reserve(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / count;
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    out.push_back(centre_ + radius_ * glm::dvec3(r * std::cos(golden * i), r * std::sin(golden * i), z));
  }
  return out;
}

BoxField::BoxField(glm::dvec3 centre, glm::dvec3 halfExtents, glm::dmat3 frame)
    : centre_(centre), half_(halfExtents), frame_(frame) {
  box_ = withMargin(corners(), 0.1);
}

double BoxField::value(glm::dvec3 p) const {
  const glm::dvec3 d = glm::abs(glm::transpose(frame_) * (p - centre_)) - half_;
  const double inside = std::min(std::max({d.x, d.y, d.z}), 0.0);
  return glm::length(glm::max(d, 0.0)) + inside;
}

glm::dvec3 BoxField::gradient(glm::dvec3 p) const {
  const glm::dvec3 q = glm::transpose(frame_) * (p - centre_);
  const glm::dvec3 d = glm::abs(q) - half_;
  const glm::dvec3 s(q.x < 0.0 ? -1.0 : 1.0, q.y < 0.0 ? -1.0 : 1.0, q.z < 0.0 ? -1.0 : 1.0);
  glm::dvec3 local(0.0);
  const glm::dvec3 out = glm::max(d, 0.0);
  if (glm::length(out) > 0.0) {
    local = s * out / glm::length(out);  // outside: away from the nearest face, edge or corner
  } else {
    const int k = d.x >= d.y && d.x >= d.z ? 0 : (d.y >= d.z ? 1 : 2);  // inside: the nearest face
    local[k] = s[k];
  }
  return frame_ * local;
}

std::vector<glm::dvec3> BoxField::corners() const {
  std::vector<glm::dvec3> out;
  for (int i = 0; i < 8; ++i)
    out.push_back(centre_ + frame_ * (half_ * glm::dvec3(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1)));
  return out;
}

std::vector<glm::dvec3> BoxField::surfaceSamples(double spacing) const {
  std::vector<glm::dvec3> out;
  for (int k = 0; k < 3; ++k) {
    const int u = (k + 1) % 3, w = (k + 2) % 3;
    for (double side : {-1.0, 1.0})
      for (double a : span(half_[u], spacing))
        for (double b : span(half_[w], spacing)) {
          glm::dvec3 q(0.0);
          q[k] = side * half_[k];
          q[u] = a;
          q[w] = b;
          out.push_back(centre_ + frame_ * q);
        }
  }
  return out;
}

std::vector<glm::dvec3> BoxField::edgeSamples(double spacing) const {
  std::vector<glm::dvec3> out;
  for (int k = 0; k < 3; ++k) {  // the four edges along axis k
    const int u = (k + 1) % 3, w = (k + 2) % 3;
    for (double su : {-1.0, 1.0})
      for (double sw : {-1.0, 1.0})
        for (double a : span(half_[k], spacing)) {
          glm::dvec3 q(0.0);
          q[k] = a;
          q[u] = su * half_[u];
          q[w] = sw * half_[w];
          out.push_back(centre_ + frame_ * q);
        }
  }
  return out;
}

}  // namespace tallow::geometry
