#pragma once
// Closed forms of the flat, normally lit half-space that the radiosity-map tests check against,
// written out independently of the shared BSSRDF code.
#include <cmath>

namespace tallow::test {

/// Normal-incidence Fresnel transmittance 1 − ((η − 1)/(η + 1))².
inline double normalTransmittance(double eta) {
  const double r = (eta - 1.0) / (eta + 1.0);
  return 1.0 - r * r;
}

/// Unpolarised Fresnel transmittance from outside at incidence cos θ (relative index η > 1).
inline double fresnelT(double cosTheta, double eta) {
  const double sinT2 = (1.0 - cosTheta * cosTheta) / (eta * eta), cosT = std::sqrt(1.0 - sinT2);
  const double rs = (cosTheta - eta * cosT) / (cosTheta + eta * cosT);
  const double rp = (eta * cosTheta - cosT) / (eta * cosTheta + cosT);
  return 1.0 - 0.5 * (rs * rs + rp * rp);
}

/// A = (1 + F_dr)/(1 − F_dr) with Jensen's fit F_dr = −1.440/η² + 0.710/η + 0.668 + 0.0636η.
inline double jensenBoundaryA(double eta) {
  const double fdr = -1.440 / (eta * eta) + 0.710 / eta + 0.668 + 0.0636 * eta;
  return (1.0 + fdr) / (1.0 - fdr);
}

/// The standard dipole's diffuse reflectance profile R_d(r) [mm⁻²] (Jensen et al. 2001, Eq. 5):
/// (α'/4π) Σ_{s ∈ {r, v}} z_s (1 + σ_tr d_s) e^{−σ_tr d_s} / d_s³, z_r = 1/σ_t', z_v = z_r (1 + 4A/3),
/// d_s = √(r² + z_s²), σ_tr = √(3 σ_a σ_t'). Its integral ∫ R_d 2πr dr is jensenTotalRd.
inline double jensenRd(double r, double sigma_a, double sigma_s, double g, double eta) {
  const double sp = sigma_s * (1.0 - g), st = sigma_a + sp, alphaP = sp / st;
  const double str = std::sqrt(3.0 * sigma_a * st);
  const double zr = 1.0 / st, zv = zr * (1.0 + 4.0 / 3.0 * jensenBoundaryA(eta));
  double sum = 0.0;
  for (const double z : {zr, zv}) {
    const double d = std::sqrt(r * r + z * z);
    sum += z * (1.0 + str * d) * std::exp(-str * d) / (d * d * d);
  }
  return alphaP / (4.0 * 3.14159265358979323846) * sum;
}

/// Total diffuse reflectance of the standard dipole, Jensen, Marschner, Levoy and Hanrahan 2001
/// (§2.4 and the BRDF approximation of §3.2, R_d = (α'/2)(1 + e^{−(4/3)A√(3(1−α'))}) e^{−√(3(1−α'))}),
/// with A = (1 + F_dr)/(1 − F_dr) and F_dr = −1.440/η² + 0.710/η + 0.668 + 0.0636η (their Eq. 4's
/// fit; the project clamps η to [1, 2.5] for it, which the materials used here satisfy).
inline double jensenTotalRd(double sigma_a, double sigma_s, double g, double eta) {
  const double sp = sigma_s * (1.0 - g);
  const double alphaP = sp / (sigma_a + sp);
  const double A = jensenBoundaryA(eta);
  const double s = std::sqrt(3.0 * (1.0 - alphaP));
  return 0.5 * alphaP * (1.0 + std::exp(-4.0 / 3.0 * A * s)) * std::exp(-s);
}

}  // namespace tallow::test
