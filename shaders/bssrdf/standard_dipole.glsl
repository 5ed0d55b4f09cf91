// The standard dipole (Jensen, Marschner, Levoy and Hanrahan 2001). Conventions:
// shaders/bssrdf/real.glsl; coefficients (z_r, z_v, σ_tr, α', A from the F_dr fit):
// shaders/bssrdf/coefficients.glsl.
#ifdef TALLOW_GLSL
#include "bssrdf/coefficients.glsl"
#endif

// Spatially resolved diffuse reflectance of a point source at depth z_r below a planar boundary
// and its image at height z_v (Jensen et al. 2001, Eq. 5):
//   R_d(r) = α'/(4π) [ z_r (1 + σ_tr d_r) e^{−σ_tr d_r}/d_r³ + z_v (1 + σ_tr d_v) e^{−σ_tr d_v}/d_v³ ],
//   d_r = √(r² + z_r²), d_v = √(r² + z_v²).
// Its integral ∫₀^∞ R_d 2πr dr is (α'/2)(1 + e^{−(4/3)A√(3(1−α'))}) e^{−√(3(1−α'))} (tested).
// Both terms are positive, so the scale is the value.
TALLOW_FN BssrdfEval standardDipoleRd(real r, BssrdfCoefficients k) {
  real r2 = r * r;
  real dr = sqrt(r2 + k.zr * k.zr);
  real dv = sqrt(r2 + k.zv * k.zv);
  real sr = k.sigmaTr * dr;
  real sv = k.sigmaTr * dv;
  real termR = k.zr * (real(1) + sr) * exp(-sr) / (dr * dr * dr);
  real termV = k.zv * (real(1) + sv) * exp(-sv) / (dv * dv * dv);
  BssrdfEval e;
  e.sd = k.alphaP / (real(4) * BSSRDF_PI) * (termR + termV);
  e.scale = e.sd;
  return e;
}

// S_d(x_i, w_i; x_o) = R_d(|x_o − x_i|)/π: the standard dipole depends on the distance only.
TALLOW_FN BssrdfEval standardDipole(real3 xi, real3 xo, BssrdfCoefficients k) {
  BssrdfEval e = standardDipoleRd(length(xo - xi), k);
  e.sd = e.sd / BSSRDF_PI;
  e.scale = e.scale / BSSRDF_PI;
  return e;
}

// ∫₀^∞ R_d 2πr dr, (α'/2)(1 + e^{−(4/3)A√(3(1−α'))}) e^{−√(3(1−α'))} (Jensen et al. 2001), with their
// boundary term A = (1 + F_dr)/(1 − F_dr): the total diffuse reflectance, a function of α' and η
// alone (method=burley's A; a subsurface colour's inversion, sss/bssrdf/subsurface_appearance.h).
TALLOW_FN real standardDipoleTotalRd(BssrdfCoefficients k) {
  real s = sqrt(real(3) * (real(1) - k.alphaP));
  return real(0.5) * k.alphaP * (real(1) + exp(real(-4) / real(3) * k.aJensen * s)) * exp(-s);
}
