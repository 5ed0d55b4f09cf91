#pragma once
// The melting candle (issues 4, 16 and 35): a wax pillar with a wick that burns down, a liquid pool
// widening under a flat surface, a thin rim standing above it, drips that run down the side and
// freeze, a puddle at the foot, the wax's volume conserved against what the flame consumes. The
// candle at t is a closed-form signed distance written once in shaders/fields/candle.glsl (its
// header describes the model): value() and gradient() evaluate those lines in double, the GPU
// evaluates them in float per lattice sample (GpuCandleField). Every t is computed from t alone, so
// the same t gives the same field whether the animation plays forward or jumps.
#include <cmath>
#include <cstdint>

#include "geometry/candle_shape.h"
#include "geometry/scalar_field.h"

namespace tallow::geometry {

struct CandleParams {
  static constexpr int kMaxDrips = candle_f64::CANDLE_MAX_DRIPS;  ///< uniforms reserved on the GPU

  double radius = 0.02;          ///< wax cylinder radius, metres
  double height = 0.065;         ///< height at t = 0 (base at y = 0), metres
  double durationS = 20.0;       ///< animation seconds shown (the candle stays as it is after)
  /// Real seconds one animation second stands for: 300 makes the 20 s animation 100 minutes of
  /// burning, in which a 4 cm pillar's pool widens to its wall (docs/presets.md).
  double timeScale = 300.0;
  double burnGramsPerHour = 10.0;  ///< wax the flame consumes (candle makers: 7–10 g/h)
  double waxDensity = 900.0;      ///< kg/m³, solid paraffin
  /// Real hours until the pool reaches 95% of its full radius: a candle maker's hour per inch of
  /// diameter.
  double fullPoolHours = 0.02 * 2.0 / 0.0254;
  double poolWall = 0.003;        ///< wall left at the pool's level once full: an eighth of an inch
  double poolDepth = 0.008;       ///< liquid depth on the axis once full (a quarter to half an inch)
  double rimAbovePool = 0.017;    ///< the hollowed pillar's rim above the pool
  double lip = 0.0022;            ///< the rim's thickness at its top once the pool is full
  double wickRadius = 0.001;      ///< metres
  double wickExposed = 0.005;     ///< wick above the pool (trimmed to about a quarter of an inch)
  /// The flame's emission centre (the point light) above the wick's tip, metres: where
  /// geometry::flameEmission puts it for a steady flame (tested), 2.5–4 mm below the rim from the
  /// preset's start on, surrounded by wax.
  double flameLift = 0.007;
  int dripCount = 10;            ///< overflows over the animation (≤ kMaxDrips)
  double dripRadius = 0.0016;    ///< metres
  /// Animation seconds a drip runs before it freezes (the mean; each draws 0.7–1.3 of it). Real
  /// drips freeze within seconds, which the time scale would make instant: slowed for the eye.
  double dripRunS = 1.6;
  double overflowStart = 0.8;    ///< share of the pool's full radius from which it overflows
  double puddleThickness = 0.0015;  ///< metres
  double puddleFeed = 2.0e-7;    ///< m³ a drip that reaches the table feeds its puddle, in the end
  double puddleFeedS = 2.5;      ///< animation seconds over which it feeds it (e-folding)
  std::uint32_t seed = 1;        ///< the overflows' times and places
  /// The field's length unit, metres: the band the values are clamped to is 3 voxels, and the
  /// smoothing radius smoothingIterations voxels.
  double voxelSize = 0.0005;
  /// Radius of the smooth union/difference and of the rounded edges, in voxels.
  int smoothingIterations = 2;

  /// The wax the flame consumes, m³ per animation second.
  double burnVolumeRate() const { return burnGramsPerHour * 1e-3 / 3600.0 / waxDensity * timeScale; }
  /// The pool's time constant in animation seconds: 95% of its full radius after fullPoolHours.
  double poolTauS() const { return fullPoolHours * 3600.0 / timeScale / 3.0; }

  bool operator==(const CandleParams&) const = default;
};

class CandleField final : public ScalarField {
 public:
  /// The candle at time t (seconds, clamped to [0, durationS]). Throws std::invalid_argument on
  /// bad params.
  explicit CandleField(double t, const CandleParams& params = {});

  /// Signed distance to the candle, metres, negative inside, clamped to ± bandWidth().
  double value(glm::dvec3 p) const override;
  /// Analytic gradient of value() (0 where it is clamped).
  glm::dvec3 gradient(glm::dvec3 p) const override;
  /// The candle at this t padded by the band: value ≥ 0 everywhere outside it.
  Aabb bounds() const override;

  /// Point flameLift above the wick's tip: where the flame (a light) sits. Below the rim and inside
  /// the hollow once it has formed (cupFormedS).
  glm::dvec3 flamePosition() const { return {0.0, shape_.flameY, 0.0}; }
  /// Animation seconds after which the hollow above the pool stands 90% of its full height.
  /// The meniscus's radius where the pool meets the wall, metres (the outline's fillet; at most this).
  static double meniscus() { return candle_f64::CANDLE_MENISCUS; }
  static double cupFormedS(const CandleParams& params) { return params.poolTauS() * std::log(10.0) / 1.5; }
  /// The box that holds the candle at every t (the lattice the renderer contours it on, fixed for
  /// the whole animation so that wax that does not change keeps its vertices).
  static Aabb lifetimeBounds(const CandleParams& params);
  double rimHeight() const { return shape_.height; }           ///< y of the top of the rim at this t, metres
  double poolY() const { return shape_.poolY; }                ///< y of the pool's flat free surface
  double poolRadius() const { return shape_.poolRadius; }      ///< the pool's radius, metres
  double poolDepth() const { return shape_.poolDepth; }        ///< liquid depth on the axis, metres
  /// The radius of the inside of the wall at the rim's top (where the lip begins), metres.
  double cupRadius() const { return candle_f64::candleTopInnerAt(shape_.poolRadius, glslParams()); }
  double currentCupDepth() const { return shape_.height - shape_.poolY; }  ///< the hollow: rim over pool, metres
  /// The wax's volume at this t as the model conserves it: V0 − burnt, m³.
  double volumeTarget() const { return shape_.volumeTarget; }
  int dripsStarted() const { return shape_.dripCount; }
  int dripsFrozen() const { return shape_.dripsFrozen; }
  double dripVolume() const { return shape_.volumeDrips; }     ///< outside the cylinder, m³
  double puddleVolume() const { return shape_.volumePuddle; }  ///< m³
  double puddleArea() const { return shape_.puddleArea; }      ///< footprint beside the candle, m²
  /// Whether p is in the liquid pool (within tol of it).
  bool inPool(glm::dvec3 p, double tol = 0.0) const { return candle_f64::candleInPool(p, shape_, tol); }
  /// Half-width of the band the values are clamped to (3 voxels), metres: beyond it value() is
  /// ± bandWidth().
  double bandWidth() const { return shape_.band; }
  double voxelSize() const { return params_.voxelSize; }
  double time() const { return t_; }
  const CandleParams& params() const { return params_; }
  /// The candle at this t as shaders/fields/candle.glsl takes it (GpuCandleField's uniforms).
  const candle_f64::CandleShape& shape() const { return shape_; }
  /// The params as shaders/fields/candle.glsl takes them (animation time).
  candle_f64::CandleParamsGlsl glslParams() const;

 private:
  CandleParams params_;
  double t_;
  candle_f64::CandleShape shape_;
};

}  // namespace tallow::geometry
