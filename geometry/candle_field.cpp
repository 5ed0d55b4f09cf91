#include "geometry/candle_field.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace tallow::geometry {

namespace {

const CandleParams& checked(const CandleParams& p, double t) {
  if (!(p.radius > 0.0) || !(p.height > 0.0) || !(p.durationS > 0.0) || !(p.burnFraction >= 0.0) ||
      !(p.burnFraction < 0.9) || !(p.rimWidth > 0.0) || !(p.rimWidth < 0.5 * p.radius) || !(p.cupDepth > 0.0) ||
      !(p.wickRadius > 0.0) || !(p.wickLength > 0.0) || p.dripCount < 0 || p.dripCount > CandleParams::kMaxDrips ||
      !(p.dripRadius > 0.0) || !(p.voxelSize > 0.0) || !(p.voxelSize <= p.wickRadius) || p.smoothingIterations < 0 ||
      !std::isfinite(t))
    throw std::invalid_argument("CandleParams: sizes must be > 0, rimWidth < radius / 2, burnFraction in [0, 0.9), "
                                "voxelSize ≤ wickRadius, dripCount in [0, " +
                                std::to_string(CandleParams::kMaxDrips) + "]");
  return p;
}

candle_f64::CandleParamsGlsl glslParams(const CandleParams& p) {
  candle_f64::CandleParamsGlsl g;
  g.radius = p.radius;
  g.height = p.height;
  g.burnFraction = p.burnFraction;
  g.rimWidth = p.rimWidth;
  g.cupDepth = p.cupDepth;
  g.wickRadius = p.wickRadius;
  g.wickLength = p.wickLength;
  g.flameLift = p.flameLift;
  g.dripCount = p.dripCount;
  g.dripRadius = p.dripRadius;
  g.voxelSize = p.voxelSize;
  g.smoothingIterations = p.smoothingIterations;
  return g;
}

}  // namespace

CandleField::CandleField(double t, const CandleParams& params)
    : params_(checked(params, t)),
      t_(t),
      shape_(candle_f64::candleShapeAt(std::clamp(t / params.durationS, 0.0, 1.0), glslParams(params))) {}

double CandleField::value(glm::dvec3 p) const { return candle_f64::candleFieldValue(p, shape_); }

glm::dvec3 CandleField::gradient(glm::dvec3 p) const { return candle_f64::candleFieldGradient(p, shape_); }

Aabb CandleField::bounds() const {
  // The cylinder that holds every part (candleShapeAt), padded by the band: the smooth union adds
  // at most k/4 where two parts meet, which the band covers (k/4 = half a voxel).
  const double pad = shape_.band;
  const double reach = shape_.reach + pad;
  Aabb box;
  box.extend(glm::vec3(glm::dvec3(-reach, shape_.low - pad, -reach)));
  box.extend(glm::vec3(glm::dvec3(reach, shape_.high + pad, reach)));
  return box;
}

}  // namespace tallow::geometry
