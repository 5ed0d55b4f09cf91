#pragma once
// The melting candle of issue 4 (point 1): an OpenVDB narrow-band level set of a wax cylinder with
// a wick that burns down over the animation. The top melts into a bowl-shaped cup around the flame,
// leaving a rim, and a few drips run down the side. Every t is built from scratch from closed-form
// shapes parameterised by t (OpenVDB's mesh-to-level-set, spheres, CSG and mean-curvature
// smoothing), so the same t gives the same field whether the animation plays forward or jumps.
// OpenVDB stays inside candle_field.cpp.
#include "geometry/level_set_field.h"

#include <memory>

namespace tallow::geometry {

namespace detail {
struct CandleGrid;  // the level set and the shape at one t, in candle_field.cpp (pimpl)
}

struct CandleParams {
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
  int dripCount = 3;             ///< drips that start one after the other and run down the side
  double dripRadius = 0.0015;    ///< metres
  double voxelSize = 0.0005;     ///< level-set voxel, metres
  int smoothingIterations = 2;   ///< mean-curvature flow steps that blend drips and rim

  bool operator==(const CandleParams&) const = default;
};

class CandleField final : public LevelSetField {
 public:
  /// The candle at time t (seconds, clamped to [0, durationS]). The last grid built is cached, so
  /// constructing the same (t, params) again is cheap. Throws std::invalid_argument on bad params.
  explicit CandleField(double t, const CandleParams& params = {});
  ~CandleField() override;
  CandleField(const CandleField&);
  CandleField& operator=(const CandleField&);

  /// Point in the cup flameLift above the wick's tip: where the flame (a light) sits. Below the
  /// rim and inside the cup from cupFormedS(params) on.
  glm::dvec3 flamePosition() const;
  /// Seconds after which the cup has its full depth (it deepens from 35% over the first quarter).
  static double cupFormedS(const CandleParams& params) { return 0.25 * params.durationS; }
  double rimHeight() const;       ///< y of the top of the rim at this t, metres
  double cupRadius() const;       ///< radius of the cup where it meets the rim, metres
  double currentCupDepth() const;  ///< depth of the cup below the rim on the axis, metres
  double time() const { return t_; }
  const CandleParams& params() const { return params_; }

 private:
  CandleField(std::shared_ptr<const detail::CandleGrid> grid, double t, const CandleParams& params);

  CandleParams params_;
  double t_;
  std::shared_ptr<const detail::CandleGrid> grid_;
};

}  // namespace tallow::geometry
