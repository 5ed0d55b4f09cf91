#pragma once
// Fields whose surface is known exactly: a sphere and a (rotated) box, both true signed distances,
// so |value| is the distance to the surface. The references of the geometry tests and of `tallow
// probe placement` (the box has the sharp edges and corners that vertex placement is judged on).
#include "geometry/scalar_field.h"

#include <vector>

namespace tallow::geometry {

/// value = ‖p − centre‖ − r. Bounds: the given box, or a 20% margin around the sphere.
class SphereField final : public ScalarField {
 public:
  SphereField(glm::dvec3 centre, double radius);
  SphereField(glm::dvec3 centre, double radius, Aabb box);
  double value(glm::dvec3 p) const override;
  glm::dvec3 gradient(glm::dvec3 p) const override;
  Aabb bounds() const override { return box_; }

  /// Points on the sphere about `spacing` apart (a Fibonacci lattice, ⌈4πr²/spacing²⌉ points).
  std::vector<glm::dvec3> surfaceSamples(double spacing) const;

 private:
  glm::dvec3 centre_;
  double radius_;
  Aabb box_;
};

/// A box of half-extents h about `centre`, turned by the rotation `frame` (orthonormal columns: the
/// box's axes in world coordinates): the exact signed distance, in the box's frame q = frameᵀ(p − c),
/// ‖max(|q| − h, 0)‖ outside and max_k(|q_k| − h_k) inside. Bounds: its corners' box, 20% margin.
class BoxField final : public ScalarField {
 public:
  BoxField(glm::dvec3 centre, glm::dvec3 halfExtents, glm::dmat3 frame);
  double value(glm::dvec3 p) const override;
  /// The exact gradient (unit length everywhere except on the box's medial surfaces).
  glm::dvec3 gradient(glm::dvec3 p) const override;
  Aabb bounds() const override { return box_; }

  /// Points on the six faces on square grids about `spacing` apart, every grid running to the
  /// face's edges, so the twelve edges and eight corners are among them.
  std::vector<glm::dvec3> surfaceSamples(double spacing) const;
  /// The eight corners, world coordinates.
  std::vector<glm::dvec3> corners() const;
  /// Points along the twelve edges about `spacing` apart, corners included.
  std::vector<glm::dvec3> edgeSamples(double spacing) const;

 private:
  glm::dvec3 centre_, half_;
  glm::dmat3 frame_;
  Aabb box_;
};

}  // namespace tallow::geometry
