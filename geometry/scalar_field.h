#pragma once
// A scalar field in world units whose zero level set is a surface: value < 0 inside, 0 on the
// surface, > 0 outside (issue 4, point 5). Implemented by the blob, sampled by GridSampler, meshed
// by the CPU reference mesher and (later) by GPU dual contouring.
#include "geometry/triangle_mesh.h"

#include <glm/glm.hpp>

namespace tallow::geometry {

class ScalarField {
 public:
  virtual ~ScalarField();

  /// Field value at world position p (metres); the surface is value = 0, negative inside.
  virtual double value(glm::dvec3 p) const = 0;
  /// ∇value at p, pointing outward on the surface. Default: central differences with a step of
  /// kGradientStepRelative × the largest extent of bounds(); override with an analytic one.
  virtual glm::dvec3 gradient(glm::dvec3 p) const;
  /// Central differences of value() with step h (for sampled fields: half a voxel).
  glm::dvec3 centralDifferenceGradient(glm::dvec3 p, double h) const;
  /// World-space box that contains the whole surface (value ≥ 0 everywhere outside it).
  virtual Aabb bounds() const = 0;

  /// Central-difference step relative to the size of bounds(): small against any feature, large
  /// enough that round-off (~1e-16 / step) stays far below the truncation error.
  static constexpr double kGradientStepRelative = 1e-5;

 protected:
  ScalarField() = default;
  ScalarField(const ScalarField&) = default;
  ScalarField& operator=(const ScalarField&) = default;
};

}  // namespace tallow::geometry
