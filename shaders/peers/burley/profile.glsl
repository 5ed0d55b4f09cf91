// Christensen and Burley's normalised diffusion profile (P. H. Christensen and B. Burley 2015,
// "Approximate Reflectance Profiles for Efficient Subsurface Scattering", Pixar Technical Memo
// 15-04, "the memo"), what production engines ship as their screen-space subsurface scattering
// (`method=burley`, sss/peers/burley.h). Conventions: shaders/bssrdf/real.glsl (lengths in mm).
//
//   R(r) = A (e^{−r/d} + e^{−r/(3d)}) / (8π d r)                       (the memo, §3)
// integrates over the plane to A, the total diffuse reflectance: ∫₀^∞ R(r) 2πr dr = A. Here A is
// the standard dipole's total (Jensen et al. 2001), so that the profile carries the same light as
// the image-space peer's R_d (standardDipoleTotalRd, bssrdf/standard_dipole.glsl), and d = ℓ/s with ℓ = 1/σ_t' the mean free path and s the memo's fit of
// the scaling factor for the searchlight configuration with ℓ (the memo, §5):
//   s = 1.85 − A + 7 |A − 0.8|³.
// The radius is importance-sampled exactly: r's density 2πr R(r)/A = (e^{−r/d} + 3 e^{−r/(3d)}/3)/(4d)
// is a mixture of two exponentials, of mean d (weight 1/4) and 3d (weight 3/4). Transmission through
// a thickness t (engines' "thick object" mode, Jimenez et al. 2010 with this profile as Unity HDRP
// does) is the profile's mass beyond t: ∫_t^∞ R(s) 2πs ds = A (e^{−t/d} + 3 e^{−t/(3d)}) / 4.
#ifdef TALLOW_GLSL
#include "bssrdf/coefficients.glsl"
#include "bssrdf/standard_dipole.glsl"
#endif

const real BURLEY_PI = 3.14159265358979323846;

// The memo's scaling factor s(A), searchlight configuration, ℓ the mean free path (§5).
TALLOW_FN real burleyScale(real A) {
  real x = abs(A - real(0.8));
  return real(1.85) - A + real(7) * x * x * x;
}

struct BurleyBand {
  real albedo;  // A
  real d;       // [mm]
};

TALLOW_FN BurleyBand burleyBand(BssrdfCoefficients k) {
  BurleyBand b;
  b.albedo = standardDipoleTotalRd(k);
  b.d = (real(1) / k.sigmaTp) / burleyScale(b.albedo);
  return b;
}

// R(r) [mm⁻²] at r > 0 [mm].
TALLOW_FN real burleyProfile(real r, BurleyBand b) {
  return b.albedo * (exp(-r / b.d) + exp(-r / (real(3) * b.d))) / (real(8) * BURLEY_PI * b.d * r);
}

// The density of the sampled radius [mm⁻¹] (integrates to 1 over r ≥ 0).
TALLOW_FN real burleyRadiusPdf(real r, real d) {
  return (exp(-r / d) + exp(-r / (real(3) * d))) / (real(4) * d);
}

// A radius with density burleyRadiusPdf from two uniform numbers u1 ∈ [0, 1) (which exponential)
// and u2 ∈ [0, 1) (where in it).
TALLOW_FN real burleySampleRadius(real u1, real u2, real d) {
  real scale = u1 < real(0.25) ? d : real(3) * d;
  return -scale * log(real(1) - u2);
}

// The light that crosses a thickness t [mm] of the medium, per unit of the irradiance entering it.
TALLOW_FN real burleyTransmittance(real t, BurleyBand b) {
  return real(0.25) * b.albedo * (exp(-t / b.d) + real(3) * exp(-t / (real(3) * b.d)));
}

