// Dielectric Fresnel terms, the refracted ray ω12 and the hemispherical Fresnel integrals C_φ, C_E
// (Frisvad et al. 2014, appendix A). Conventions: shaders/bssrdf/real.glsl.
#ifdef TALLOW_GLSL
#include "bssrdf/real.glsl"
#endif

// cos²θ_t = 1 − (1 − cos²θ_i)/η², written (cos²θ_i + (η − 1)(η + 1))/η² so that grazing incidence
// keeps its digits in float (1 − (1 − c²) loses c² below the rounding unit); ≤ 0: no transmitted ray.
TALLOW_FN real transmittedCos2(real cosThetaI, real eta) {
  return (cosThetaI * cosThetaI + (eta - real(1)) * (eta + real(1))) / max(eta * eta, real(1e-30));
}

// Exact unpolarised reflectance of a smooth dielectric interface (the average of the s and p
// Fresnel equations). cosThetaI: cosine of the angle of incidence, on the side the light comes
// from (its sign is ignored); eta: relative index of refraction η = η_transmitted / η_incident.
// Total internal reflection (sin θ_t ≥ 1, possible only for η < 1) and grazing incidence give 1.
TALLOW_FN real fresnelReflectance(real cosThetaI, real eta) {
  real ci = min(abs(cosThetaI), real(1));
  real cos2T = transmittedCos2(ci, eta);
  if (cos2T <= real(0)) return real(1);
  real ct = sqrt(cos2T);
  // ci + η ct > 0 here: ct = 0 is handled above.
  real rs = (ci - eta * ct) / (ci + eta * ct);
  real rp = (eta * ci - ct) / (eta * ci + ct);
  return real(0.5) * (rs * rs + rp * rp);
}

// T = 1 − R (no absorption at the interface).
TALLOW_FN real fresnelTransmittance(real cosThetaI, real eta) {
  return real(1) - fresnelReflectance(cosThetaI, eta);
}

// The refracted direction ω12 of light that arrives along −w_i at a surface with outward normal
// n_i and relative index η = η_inside / η_outside (Snell's law; the transcription in the
// radiosity-maps paper, appendix A):
//   ω12 = (1/η)((w_i·n_i) n_i − w_i) − n_i √(1 − (1 − (w_i·n_i)²)/η²).
// It always points into the medium (ω12·n_i ≤ 0), also for w_i·n_i ≤ 0 (backlit x_i: the formula
// then refracts the mirror image of w_i, which keeps the models defined). Where there is no
// transmitted ray (total internal reflection, η < 1 only; T12 = 0 there) it returns the grazing
// direction along the surface, so that the models stay finite.
TALLOW_FN real3 refractedDirection(real3 wi, real3 ni, real eta) {
  real c = dot(wi, ni);
  real3 tangential = c * ni - wi;  // minus the part of w_i along the surface, |·| = sin θ_i
  real cos2T = transmittedCos2(min(abs(c), real(1)), eta);
  if (cos2T <= real(0)) {
    real len = length(tangential);  // ≥ η > 0 here
    return len > real(0) ? tangential / len : -ni;
  }
  return tangential / eta - sqrt(cos2T) * ni;
}

// --- Hemispherical Fresnel integrals (appendix A) --------------------------------------------
// C_φ(η) = ¼(1 − 2C_1) and C_E(η) = ½(1 − 3C_2) (Eqs. 30–31), with the polynomial fits of 2C_1 and
// 3C_2 by d'Eon and Irving (2011) that appendix A lists. Numerically,
//   C_φ(η) = ½ ∫₀¹ T(μ; 1/η) μ dμ,   C_E(η) = (3/2) ∫₀¹ T(μ; 1/η) μ² dμ   (Eqs. 28–29),
// where μ is the cosine of the direction inside the medium and T(μ; 1/η) the transmittance of
// light inside the medium reaching the boundary (so with total internal reflection for η > 1):
// that is the reading of Eqs. 28–29 that the fits reproduce (sss/bssrdf/bssrdf.cpp integrates it; the
// tests compare). C_φ(1/η) is then the same integral seen from outside.
//
// The fits are usable on [0.4, 2.5] (beyond 2.5 the η ≥ 1 fit of 3C_2 runs away and C_φ turns
// negative near η = 3); η is clamped to that range so that C_φ(η) and C_φ(1/η) stay positive.
// Their largest error on [0.5, 2] is at the junction η = 1, where 2C_1 = 0.0044 and
// 3C_2 = −0.0068 instead of 0 (docs/bssrdf-models.md).
//
// The polynomials are evaluated in powers of u = η − 1. The coefficients are the paper's, exactly
// re-expanded (rational arithmetic) around η = 1: the printed form of the η ≥ 1 fit of 3C_2 sums
// terms of ±1641 to results near 0.01, which loses 3–4 digits in float; this form loses < 1.
const real BSSRDF_FIT_ETA_MIN = 0.4;
const real BSSRDF_FIT_ETA_MAX = 2.5;

// 2C_1(η), d'Eon and Irving (2011): η < 1: 0.919317 − 3.4793η + 6.75335η² − 7.80989η³
// + 4.98554η⁴ − 1.36881η⁵; η ≥ 1: −9.23372 + 22.2272η − 20.9292η² + 10.2291η³ − 2.54396η⁴
// + 0.254913η⁵.
TALLOW_FN real fresnelMoment2C1(real eta) {
  real e = clamp(eta, BSSRDF_FIT_ETA_MIN, BSSRDF_FIT_ETA_MAX);
  real u = e - real(1);
  if (e < real(1))
    return real(0.000207) +
           u * (real(-0.30416) +
                u * (real(-0.45118) + u * (real(-1.55583) + u * (real(-1.85851) + u * real(-1.36881)))));
  return real(0.004333) +
         u * (real(2.154825) + u * (real(-2.95653) + u * (real(2.60239) + u * (real(-1.269395) + u * real(0.254913)))));
}

// 3C_2(η), d'Eon and Irving (2011): η < 1: 0.828421 − 2.62051η + 3.36231η² − 1.95284η³
// + 0.236494η⁴ + 0.145787η⁵; η ≥ 1: −1641.1 + 135.926/η³ − 656.175/η² + 1376.53/η + 1213.67η
// − 568.556η² + 164.798η³ − 27.0181η⁴ + 1.91826η⁵ (evaluated as η⁻³ times a polynomial of degree 8).
TALLOW_FN real fresnelMoment3C2(real eta) {
  real e = clamp(eta, BSSRDF_FIT_ETA_MIN, BSSRDF_FIT_ETA_MAX);
  real u = e - real(1);
  if (e < real(1))
    return real(-0.000338) +
           u * (real(-0.079499) +
                u * (real(0.380624) + u * (real(0.451006) + u * (real(0.965429) + u * real(0.145787)))));
  real p = real(-0.00684) +
           u * (real(0.49238) +
                u * (real(7.99118) +
                     u * (real(-14.23094) +
                          u * (real(31.5047) +
                               u * (real(-39.72554) +
                                    u * (real(29.38258) + u * (real(-11.67202) + u * real(1.91826))))))));
  return p / (e * e * e);
}

// C_φ(η) = ¼(1 − 2C_1(η))   (Eq. 30 with the fit).
TALLOW_FN real cPhiPolynomial(real eta) { return real(0.25) * (real(1) - fresnelMoment2C1(eta)); }

// C_E(η) = ½(1 − 3C_2(η))   (Eq. 31 with the fit).
TALLOW_FN real cEPolynomial(real eta) { return real(0.5) * (real(1) - fresnelMoment3C2(eta)); }
