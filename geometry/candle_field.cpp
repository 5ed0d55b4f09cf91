#include "geometry/candle_field.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace tallow::geometry {

namespace {

const CandleParams& checked(const CandleParams& p, double t) {
  const bool sizes = p.radius > 0.0 && p.height > 0.0 && p.durationS > 0.0 && p.timeScale > 0.0 &&
                     p.burnGramsPerHour >= 0.0 && p.waxDensity > 0.0 && p.fullPoolHours > 0.0 &&
                     p.poolWall > 0.0 && p.poolWall < 0.5 * p.radius && p.poolDepth >= 0.0 && p.rimAbovePool > 0.0 &&
                     p.lip > 0.0 && p.lip <= p.poolWall && p.wickRadius > 0.0 && p.wickExposed > 0.0 &&
                     p.flameLift >= 0.0 && p.dripRadius > 0.0 && p.dripRunS > 0.0 && p.overflowStart > 0.0 &&
                     p.overflowStart < 1.0 && p.puddleThickness > 0.0 && p.puddleFeed >= 0.0 && p.puddleFeedS > 0.0 &&
                     p.voxelSize > 0.0 && p.voxelSize <= p.wickRadius;
  if (!sizes || p.dripCount < 0 || p.dripCount > CandleParams::kMaxDrips || p.smoothingIterations < 0 ||
      !std::isfinite(t))
    throw std::invalid_argument("CandleParams: sizes and rates must be > 0, poolWall < radius / 2, lip ≤ poolWall, "
                                "overflowStart in (0, 1), voxelSize ≤ wickRadius, dripCount in [0, " +
                                std::to_string(CandleParams::kMaxDrips) + "]");
  // The candle must not burn away within the animation: a tenth of its volume is left at the end.
  const double volume = 3.14159265358979323846 * p.radius * p.radius * p.height;
  if (p.burnVolumeRate() * p.durationS > 0.9 * volume)
    throw std::invalid_argument("CandleParams: the flame would burn more than 90% of the candle in durationS "
                                "(lower burnGramsPerHour or timeScale)");
  return p;
}

candle_f64::CandleParamsGlsl toGlsl(const CandleParams& p) {
  candle_f64::CandleParamsGlsl g;
  g.radius = p.radius;
  g.height = p.height;
  g.burnRate = p.burnVolumeRate();
  g.poolTau = p.poolTauS();
  g.poolWall = p.poolWall;
  g.poolDepth = p.poolDepth;
  g.rimAbovePool = p.rimAbovePool;
  g.lip = p.lip;
  g.wickRadius = p.wickRadius;
  g.wickExposed = p.wickExposed;
  g.flameLift = p.flameLift;
  g.dripCount = p.dripCount;
  g.dripRadius = p.dripRadius;
  g.dripRun = p.dripRunS;
  g.overflowStart = p.overflowStart;
  g.overflowEnd = 0.95 * p.durationS;
  g.puddleThickness = p.puddleThickness;
  g.puddleFeed = p.puddleFeed;
  g.puddleFeedTau = p.puddleFeedS;
  g.seed = static_cast<int>(p.seed);
  g.voxelSize = p.voxelSize;
  g.smoothingIterations = p.smoothingIterations;
  return g;
}

}  // namespace

CandleField::CandleField(double t, const CandleParams& params)
    : params_(checked(params, t)),
      t_(t),
      shape_(candle_f64::candleShapeAt(std::clamp(t, 0.0, params.durationS), toGlsl(params))) {}

candle_f64::CandleParamsGlsl CandleField::glslParams() const { return toGlsl(params_); }

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

Aabb CandleField::lifetimeBounds(const CandleParams& params) {
  // The tallest candle is the first; the widest reach is the puddle's, which only grows, so the end
  // holds it; a drip reaches out by its bead. Both padded by the band and a voxel.
  const CandleField first(0.0, params), last(params.durationS, params);
  const double pad = first.bandWidth() + params.voxelSize;
  const double reach = std::max({first.shape_.reach, last.shape_.reach, params.radius + 3.0 * params.dripRadius}) + pad;
  const double high = std::max(first.shape_.high, last.shape_.high) + pad;
  Aabb box;
  box.extend(glm::vec3(glm::dvec3(-reach, -pad, -reach)));
  box.extend(glm::vec3(glm::dvec3(reach, high, reach)));
  return box;
}

}  // namespace tallow::geometry
