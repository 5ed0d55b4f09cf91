#pragma once
// The melting candle of issue 4 (point 1): a wax cylinder with a wick that burns down over the
// animation; the top melts into a bowl-shaped cup around the flame, leaving a rim, and a few drips
// run down the side. Since issue 16 (points 2 and 3) the candle at t is a closed-form signed
// distance written once in shaders/fields/candle.glsl (see its header for the shapes and why not a
// NanoVDB grid): value() and gradient() evaluate those lines in double, the GPU evaluates them in
// float per lattice sample (GpuCandleField). Every t is computed from t alone, so the same t gives
// the same field whether the animation plays forward or jumps; constructing one costs a few
// microseconds (no OpenVDB, no cache).
#include "geometry/candle_shape.h"
#include "geometry/scalar_field.h"

namespace tallow::geometry {

struct CandleParams {
  static constexpr int kMaxDrips = candle_f64::CANDLE_MAX_DRIPS;  ///< uniforms reserved on the GPU

  double radius = 0.02;          ///< wax cylinder radius, metres
  double height = 0.08;          ///< height at t = 0 (base at y = 0), metres
  double durationS = 20.0;       ///< seconds from lighting to the end of the animation
  double burnFraction = 0.5;     ///< fraction of the height burnt away at t = durationS
  double rimWidth = 0.003;       ///< wall left between the cup and the outside, metres
  double cupDepth = 0.010;       ///< depth of the melted cup once fully formed, metres
  double wickRadius = 0.001;     ///< metres
  double wickLength = 0.004;     ///< how far the wick stands above the bottom of the cup, metres
  /// The flame's centre (the point light) above the wick's tip, metres. With the cup formed the
  /// flame is wickLength + flameLift above its bottom: 3 mm below the rim, surrounded by wax.
  double flameLift = 0.003;
  int dripCount = 3;             ///< drips that start one after the other and run down the side (≤ kMaxDrips)
  double dripRadius = 0.0015;    ///< metres
  /// The field's length unit, metres: the band the values are clamped to is 3 voxels, and the
  /// smoothing radius smoothingIterations voxels. (The voxel of the OpenVDB level set that the
  /// candle was until issue 16.)
  double voxelSize = 0.0005;
  /// Radius of the smooth union/difference and of the rounded edges, in voxels: stands in for the
  /// mean-curvature flow steps that blended drips and rim in the level set.
  int smoothingIterations = 2;

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

  /// Point in the cup flameLift above the wick's tip: where the flame (a light) sits. Below the
  /// rim and inside the cup from cupFormedS(params) on.
  glm::dvec3 flamePosition() const { return {0.0, shape_.flameY, 0.0}; }
  /// Seconds after which the cup has its full depth (it deepens from 35% over the first quarter).
  static double cupFormedS(const CandleParams& params) { return 0.25 * params.durationS; }
  double rimHeight() const { return shape_.height; }         ///< y of the top of the rim at this t, metres
  double cupRadius() const { return shape_.cupRadius; }      ///< radius of the cup where it meets the rim, metres
  double currentCupDepth() const { return shape_.cupDepth; }  ///< depth of the cup below the rim on the axis, metres
  /// Half-width of the band the values are clamped to (3 voxels), metres: beyond it value() is
  /// ± bandWidth(), as the narrow-band level set it replaces was.
  double bandWidth() const { return shape_.band; }
  double voxelSize() const { return params_.voxelSize; }
  double time() const { return t_; }
  const CandleParams& params() const { return params_; }
  /// The candle at this t as shaders/fields/candle.glsl takes it (GpuCandleField's uniforms).
  const candle_f64::CandleShape& shape() const { return shape_; }

 private:
  CandleParams params_;
  double t_;
  candle_f64::CandleShape shape_;
};

}  // namespace tallow::geometry
