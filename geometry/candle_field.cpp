#include "geometry/candle_field.h"

#include "geometry/openvdb_support.h"

#include <openvdb/openvdb.h>
#include <openvdb/tools/Composite.h>
#include <openvdb/tools/LevelSetFilter.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace tallow::geometry {

struct detail::CandleGrid : LevelSetGrid {
  // Closed-form shape parameters at this t (metres).
  double rimHeight = 0.0;
  double cupDepth = 0.0;
  double cupRadius = 0.0;
  glm::dvec3 flame{0.0};
};

namespace {

double smoothstep(double a, double b, double x) {
  const double u = std::clamp((x - a) / (b - a), 0.0, 1.0);
  return u * u * (3.0 - 2.0 * u);
}

/// The candle at s = t / durationS ∈ [0, 1], from scratch: nothing depends on earlier frames.
std::shared_ptr<detail::CandleGrid> build(double s, const CandleParams& p) {
  initialiseOpenVdb();
  auto out = std::make_shared<detail::CandleGrid>();
  const auto xform = openvdb::math::Transform::createLinearTransform(p.voxelSize);

  // Height burns down linearly; the cup forms quickly after lighting (a shallow dent at t = 0).
  const double h = p.height * (1.0 - p.burnFraction * s);
  const double d = p.cupDepth * (0.35 + 0.65 * smoothstep(0.0, 0.25, s));
  const double cupR = p.radius - p.rimWidth;
  out->rimHeight = h;
  out->cupDepth = d;
  out->cupRadius = cupR;

  auto wax = cylinderLevelSet(p.radius, 0.0, h, *xform);

  // Drips: chains of spheres hugging the side, each starting at its own time and running down
  // over 30% of the animation to its own length, thickening into a bead at the bottom end.
  for (int i = 0; i < p.dripCount; ++i) {
    const double start = 0.08 + 0.8 * i / std::max(1, p.dripCount);
    const double maxLength = p.height * (0.2 + 0.06 * ((2 * i) % 3));
    const double length = std::min(maxLength * smoothstep(start, start + 0.3, s), h - 2.0 * p.dripRadius);
    if (length < p.dripRadius) continue;
    const double angle = 2.0 * std::numbers::pi * (0.11 + 0.382 * i);
    const glm::dvec3 dir(std::cos(angle), 0.0, std::sin(angle));
    const double top = h - 0.002;
    const int steps = std::max(1, static_cast<int>(std::ceil(length / (0.5 * p.dripRadius))));
    for (int k = 0; k <= steps; ++k) {
      const double u = static_cast<double>(k) / steps;
      const double r = p.dripRadius * (0.7 + 0.5 * u * u);
      const glm::dvec3 centre = dir * (p.radius - 0.2 * r) + glm::dvec3(0.0, top - u * length, 0.0);
      auto bead = sphereLevelSet(r, centre, p.voxelSize);
      openvdb::tools::csgUnion(*wax, *bead);
    }
  }

  // The cup: a spherical bowl of depth d that meets the top at radius cupR, leaving the rim.
  const double bowlR = (cupR * cupR + d * d) / (2.0 * d);
  auto bowl = sphereLevelSet(bowlR, glm::dvec3(0.0, h - d + bowlR, 0.0), p.voxelSize);
  openvdb::tools::csgDifference(*wax, *bowl);

  // Mean-curvature flow rounds the rim's edges and blends the drips into the side.
  if (p.smoothingIterations > 0) {
    openvdb::tools::LevelSetFilter<openvdb::FloatGrid> filter(*wax);
    for (int k = 0; k < p.smoothingIterations; ++k) filter.meanCurvature();
  }

  // The wick stands in the middle of the cup, rooted in the wax below it (after smoothing, so
  // that the thin wick keeps its shape).
  const double cupBottom = h - d;
  auto wick = cylinderLevelSet(p.wickRadius, cupBottom - 0.004, cupBottom + p.wickLength, *xform);
  openvdb::tools::csgUnion(*wax, *wick);

  out->flame = glm::dvec3(0.0, cupBottom + p.wickLength + p.flameLift, 0.0);
  out->grid = wax;
  return out;
}

/// The last grid built (for any CandleField), so that re-constructing the same t is cheap.
std::shared_ptr<const detail::CandleGrid> cachedBuild(double s, const CandleParams& p) {
  static std::mutex mutex;
  static double lastS = -1.0;
  static CandleParams lastParams;
  static std::shared_ptr<const detail::CandleGrid> last;
  const std::lock_guard lock(mutex);
  if (!last || lastS != s || !(lastParams == p)) {
    last = build(s, p);
    lastS = s;
    lastParams = p;
  }
  return last;
}

const CandleParams& checked(const CandleParams& p, double t) {
  if (!(p.radius > 0.0) || !(p.height > 0.0) || !(p.durationS > 0.0) || !(p.burnFraction >= 0.0) ||
      !(p.burnFraction < 0.9) || !(p.rimWidth > 0.0) || !(p.rimWidth < 0.5 * p.radius) || !(p.cupDepth > 0.0) ||
      !(p.wickRadius > 0.0) || !(p.wickLength > 0.0) || p.dripCount < 0 || !(p.dripRadius > 0.0) ||
      !(p.voxelSize > 0.0) || !(p.voxelSize <= p.wickRadius) || p.smoothingIterations < 0 ||
      !std::isfinite(t))
    throw std::invalid_argument("CandleParams: sizes must be > 0, rimWidth < radius / 2, burnFraction in [0, 0.9), voxelSize ≤ wickRadius");
  return p;
}
}  // namespace

CandleField::CandleField(double t, const CandleParams& params)
    : CandleField(cachedBuild(std::clamp(t / checked(params, t).durationS, 0.0, 1.0), params), t, params) {}

CandleField::CandleField(std::shared_ptr<const detail::CandleGrid> grid, double t, const CandleParams& params)
    : LevelSetField(grid, params.voxelSize, kHalfWidthVoxels * params.voxelSize), params_(params), t_(t), grid_(std::move(grid)) {}

CandleField::~CandleField() = default;
CandleField::CandleField(const CandleField&) = default;
CandleField& CandleField::operator=(const CandleField&) = default;

glm::dvec3 CandleField::flamePosition() const { return grid_->flame; }
double CandleField::rimHeight() const { return grid_->rimHeight; }
double CandleField::cupRadius() const { return grid_->cupRadius; }
double CandleField::currentCupDepth() const { return grid_->cupDepth; }

}  // namespace tallow::geometry
