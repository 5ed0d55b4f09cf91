#pragma once
// The flame of a burning candle at time t (issue 35, point 4): a diffusion flame's teardrop standing
// on the wick, its size from the wick's exposed length, its look written once in
// shaders/flame/flame_profile.glsl (the outline; the radiance: a blackbody profile from 1600 K at the
// edge to about 1980 K in the core, a dark cone above the wick, a faint blue base, a soft edge) and a
// flicker that is a deterministic function of t: a few per cent of brightness and height and a sway
// of about a millimetre at the tip (`flame.flicker` scales it; 0 is a steady flame). The point light
// that stands in for the flame takes its flux and its emission centre from the same profile, so the
// light's colour is the drawn flame's colour and the light follows the drawn flame every frame.
// Lengths are the candle field's units (metres before the object's transform), y up.
#include <glm/glm.hpp>

#include "geometry/candle_field.h"

namespace tallow::geometry {

/// The flame's size for a wick: a flame a few wick lengths tall (ours: 3.6 × the exposed length,
/// 18 mm for the default 5 mm), its widest half-width 0.26 of that.
inline constexpr double kFlameHeightPerWick = 3.6;
inline constexpr double kFlameWidthShare = 0.26;
/// The flame's base (v = 0) lies this far below the wick's tip.
inline constexpr double kFlameBaseBelowTip = 0.001;

struct CandleFlame {
  glm::dvec3 base{0.0};   ///< v = 0 on the axis
  double height = 0.0;    ///< base to tip (v = 1), flicker included
  double halfWidth = 0.0;  ///< at the widest
  /// Where the sway moves each height v of the flame: base + v·height·up + v²·sway (the tip sways
  /// most, the base not at all).
  glm::dvec3 sway{0.0};
  double gain = 1.0;  ///< the brightness flicker, ≈ 1
};

/// The candle's flame at the field's time, with `flicker` (the registry's flame.flicker: 0 steady,
/// 1 a gentle flicker; deterministic in t).
CandleFlame candleFlameAt(const CandleField& field, double flicker);

/// What the flame emits, from flameProfile integrated over its sheet.
struct FlameEmission {
  /// ∫ profile dA over the sheet (linear sRGB, per unit radiance scale, m²): the light's intensity is
  /// this times the drawn flame's radiance scale.
  glm::dvec3 flux{0.0};
  glm::dvec3 centre{0.0};  ///< the emission centre: the luminance-weighted mean point of the sheet
  /// Luminance (Y) of the flux; radiance scale = the light's luminous intensity / this.
  double luminance() const { return 0.2126 * flux.x + 0.7152 * flux.y + 0.0722 * flux.z; }
};
FlameEmission flameEmission(const CandleFlame& flame);

/// The flame's relative radiance at (x, v) of its sheet (shaders/flame/flame_profile.glsl, in double).
glm::dvec3 flameProfileAt(double x, double v);

/// What a flame's sheet (world base, unit axis, height, widest half-width, sway at the tip) shows to a
/// viewer at `origin` looking along unit `dir`, per unit of radiance scale
/// (shaders/flame/flame_mirror.glsl, in double).
glm::dvec3 flameSeenAlong(const glm::dvec3& origin, const glm::dvec3& dir, const glm::dvec3& base, const glm::dvec3& up,
                          double height, double halfWidth, const glm::dvec3& sway);

/// Linear sRGB of a blackbody at `kelvin`, luminance 1 (shaders/flame/blackbody.glsl).
glm::dvec3 blackbodyColour(double kelvin);

}  // namespace tallow::geometry
