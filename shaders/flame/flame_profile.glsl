// The candle flame's look, written once for GLSL and C++ (the conventions of
// shaders/bssrdf/real.glsl): its outline and its radiance at each point of the camera-facing sheet it
// is drawn on (shaders/flame.frag), which geometry::CandleFlame integrates for the point light that
// stands in for it (its flux and its emission centre), so that the light and the drawn flame are
// the same emission. Coordinates: v from the flame's base (a millimetre below the wick's tip, v = 0)
// to its tip (v = 1); x across, in half-widths of the widest point.
//
// A diffusion flame's teardrop: width ∝ √v (1 − v)^0.85, round at the base, widest at 37% of the
// height, a long taper to the tip. Its light: the luminous zone (glowing soot) a blackbody whose
// temperature rises from 1600 K at the edge to about 1980 K in the core (whiter there), dimmer in the
// dark cone just above the wick where the wax vapour has not yet burnt, fading toward the tip; a faint
// blue base where fuel meets air beside the wick (CH and C₂ emission, not a blackbody); a soft edge,
// no hard outline: the radiance falls to 0 from 55% to 125% of the outline's half-width.
#ifdef TALLOW_GLSL
#include "flame/blackbody.glsl"
#endif

const real FLAME_WIDEST = 0.41071;      // √v (1 − v)^0.85 at its widest, v = 0.5/1.35
const real FLAME_EDGE_REACH = 1.25;     // the soft edge's outer end, in half-widths of the outline
const real FLAME_EDGE_START = 0.55;     // and its inner end
const real FLAME_TIP_REACH = 1.08;      // the tip fades out by here

// The outline's half-width at height v, in half-widths of the widest point.
TALLOW_FN real flameOutline(real v) {
  real c = clamp(v, real(0), real(1));
  return sqrt(c) * pow(real(1) - c, real(0.85)) / FLAME_WIDEST;
}

// The flame's radiance at (x, v), linear sRGB, relative (geometry::CandleFlame scales it).
TALLOW_FN real3 flameProfile(real x, real v) {
  real w = flameOutline(v);
  real across = w > real(1e-6) ? abs(x) / w : real(1e6);
  real edge = real(1) - smoothstep(FLAME_EDGE_START, FLAME_EDGE_REACH, across);
  if (!(edge > real(0))) return real3(real(0));
  real rise = smoothstep(real(0.03), real(0.25), v);
  real fade = real(1) - smoothstep(real(0.55), FLAME_TIP_REACH, v);
  real dark = (real(1) - smoothstep(real(0), real(0.25), v)) * (real(1) - smoothstep(real(0), real(0.6), across));
  real core = exp(-across * across / real(0.3)) * smoothstep(real(0.08), real(0.35), v) *
              (real(1) - smoothstep(real(0.45), real(0.85), v));
  real kelvin = real(1600) + real(380) * core;
  real luminous = edge * rise * fade * (real(1) - real(0.7) * dark) * (real(0.3) + real(0.7) * core);
  real blue = real(0.08) * (real(1) - smoothstep(real(0), real(0.2), v)) * smoothstep(real(0.15), real(0.65), across) * edge;
  return luminous * blackbodyRgb(kelvin) + blue * real3(real(0.2), real(0.35), real(1));
}
