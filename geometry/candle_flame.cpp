#include "geometry/candle_flame.h"

#include <cmath>
#include <numbers>

#include "gpu/glsl_shared.h"

namespace tallow::geometry {

namespace flame_f64 {
using real = double;
#include "gpu/glsl_real_types.inc"
#include "shaders/flame/blackbody.glsl"
#include "shaders/flame/flame_profile.glsl"
#include "shaders/flame/flame_mirror.glsl"
}  // namespace flame_f64

namespace {

/// The profile's integrals, which do not depend on t (size, sway and gain scale and move them):
/// ∫∫ profile dx dv over the sheet, and the luminance-weighted means of v and v².
struct ProfileMoments {
  glm::dvec3 flux{0.0};
  double meanV = 0.0, meanV2 = 0.0;
};

const ProfileMoments& moments() {
  static const ProfileMoments m = [] {
    // Midpoint sums on a grid fine enough that the soft edge and the tip are resolved (the sums
    // change by under 0.1% from 96 × 128 to 192 × 256).
    constexpr int kAcross = 96, kUp = 128;
    const double xMax = flame_f64::FLAME_EDGE_REACH, vMax = flame_f64::FLAME_TIP_REACH;
    const double dx = 2.0 * xMax / kAcross, dv = vMax / kUp;
    ProfileMoments out;
    double weight = 0.0;
    for (int j = 0; j < kUp; ++j) {
      const double v = (j + 0.5) * dv;
      for (int i = 0; i < kAcross; ++i) {
        const double x = -xMax + (i + 0.5) * dx;
        const glm::dvec3 r = flame_f64::flameProfile(x, v);
        out.flux += r * dx * dv;
        const double y = (0.2126 * r.x + 0.7152 * r.y + 0.0722 * r.z) * dx * dv;
        weight += y;
        out.meanV += y * v;
        out.meanV2 += y * v * v;
      }
    }
    out.meanV /= weight;
    out.meanV2 /= weight;
    return out;
  }();
  return m;
}

}  // namespace

CandleFlame candleFlameAt(const CandleField& field, double flicker) {
  const double t = field.time();
  const double twoPi = 2.0 * std::numbers::pi;
  CandleFlame f;
  f.base = {0.0, field.shape().wickTop - kFlameBaseBelowTip, 0.0};
  const double steady = kFlameHeightPerWick * field.params().wickExposed;
  // A gentle flicker: a few incommensurate slow waves, deterministic in t, scaled by `flicker`
  // (1: about ±2.5% of brightness, ±3% of height, a millimetre of sway at the tip).
  const double bright = 0.6 * std::sin(twoPi * 1.7 * t + 0.3) + 0.3 * std::sin(twoPi * 3.1 * t + 1.1) +
                        0.1 * std::sin(twoPi * 11.3 * t + 2.3);
  const double tall = 0.7 * std::sin(twoPi * 1.3 * t + 0.8) + 0.3 * std::sin(twoPi * 4.3 * t + 2.0);
  f.gain = 1.0 + flicker * 0.025 * bright;
  f.height = steady * (1.0 + flicker * 0.03 * tall);
  f.halfWidth = kFlameWidthShare * steady;
  f.sway = flicker * 0.0012 *
           glm::dvec3(std::sin(twoPi * 0.7 * t + 0.4) + 0.25 * std::sin(twoPi * 2.3 * t), 0.0,
                      std::sin(twoPi * 0.53 * t + 1.9) + 0.25 * std::sin(twoPi * 1.9 * t + 0.7));
  return f;
}

FlameEmission flameEmission(const CandleFlame& flame) {
  const ProfileMoments& m = moments();
  FlameEmission e;
  e.flux = m.flux * (flame.halfWidth * flame.height);
  e.centre = flame.base + glm::dvec3(0.0, m.meanV * flame.height, 0.0) + m.meanV2 * flame.sway;
  return e;
}

glm::dvec3 blackbodyColour(double kelvin) { return flame_f64::blackbodyRgb(kelvin); }

glm::dvec3 flameProfileAt(double x, double v) { return flame_f64::flameProfile(x, v); }

glm::dvec3 flameSeenAlong(const glm::dvec3& origin, const glm::dvec3& dir, const glm::dvec3& base, const glm::dvec3& up,
                          double height, double halfWidth, const glm::dvec3& sway) {
  return flame_f64::flameSeenAlong(origin, dir, base, up, height, halfWidth, sway);
}

}  // namespace tallow::geometry
