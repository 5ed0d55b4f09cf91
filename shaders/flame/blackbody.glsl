// The colour of a blackbody, written once for GLSL and C++ (the conventions of
// shaders/bssrdf/real.glsl). Planck's law B(λ, T) ∝ λ⁻⁵ / (e^(c₂/λT) − 1), c₂ = hc/k = 14387.77 µm·K,
// summed over 380–780 nm in 5 nm steps against the CIE 1931 colour-matching functions — in the
// multi-lobe Gaussian fit of Wyman, Sloan and Shirley, "Simple Analytic Approximations to the CIE XYZ
// Color Matching Functions", JCGT 2(2), 2013 (their piecewise Gaussians, coefficients as published)
// — to XYZ, then to linear sRGB by IEC 61966-2-1's matrix (Rec. 709 primaries, D65), normalised to
// luminance Y = 1. A candle flame's orange at 1800–1900 K lies a little outside sRGB's gamut (its
// blue comes out slightly negative): clamped at 0, then renormalised. The flame's drawn colour and
// its light's colour both come from here (geometry/candle_flame.h, shaders/flame.frag).
#ifdef TALLOW_GLSL
#include "common/shared.glsl"
#include "bssrdf/real.glsl"
#endif

// One lobe of the fit: a Gaussian with a different width on each side of its mean.
TALLOW_FN real blackbodyLobe(real x, real mean, real below, real above) {
  real t = (x - mean) / (x < mean ? below : above);
  return exp(real(-0.5) * t * t);
}

// x̄, ȳ, z̄ at λ nanometres (Wyman, Sloan and Shirley 2013, Eq. 2).
TALLOW_FN real3 blackbodyCmf(real lambda) {
  real x = real(1.056) * blackbodyLobe(lambda, real(599.8), real(37.9), real(31.0)) +
           real(0.362) * blackbodyLobe(lambda, real(442.0), real(16.0), real(26.7)) -
           real(0.065) * blackbodyLobe(lambda, real(501.1), real(20.4), real(26.2));
  real y = real(0.821) * blackbodyLobe(lambda, real(568.8), real(46.9), real(40.5)) +
           real(0.286) * blackbodyLobe(lambda, real(530.9), real(16.3), real(31.1));
  real z = real(1.217) * blackbodyLobe(lambda, real(437.0), real(11.8), real(36.0)) +
           real(0.681) * blackbodyLobe(lambda, real(459.0), real(26.0), real(13.8));
  return real3(x, y, z);
}

// Planck's spectral radiance at λ nanometres and T kelvin, up to a constant factor.
TALLOW_FN real blackbodyPlanck(real lambda, real kelvin) {
  real l = lambda * real(1e-3);  // µm
  return real(1) / (l * l * l * l * l * (exp(real(14387.77) / (l * kelvin)) - real(1)));
}

// Linear sRGB of a blackbody at T kelvin, luminance (Y) 1.
TALLOW_FN real3 blackbodyRgb(real kelvin) {
  real3 xyz = real3(real(0));
  for (int i = 0; i <= 80; ++i) {
    real lambda = real(380) + real(5) * real(i);
    xyz += blackbodyPlanck(lambda, kelvin) * blackbodyCmf(lambda);
  }
  xyz = xyz / max(xyz.y, real(1e-30));
  real3 rgb = real3(real(3.2406) * xyz.x - real(1.5372) * xyz.y - real(0.4986) * xyz.z,
                    real(-0.9689) * xyz.x + real(1.8758) * xyz.y + real(0.0415) * xyz.z,
                    real(0.0557) * xyz.x - real(0.2040) * xyz.y + real(1.0570) * xyz.z);
  rgb = max(rgb, real3(real(0)));
  real luminance = real(0.2126) * rgb.x + real(0.7152) * rgb.y + real(0.0722) * rgb.z;
  return rgb / max(luminance, real(1e-30));
}
