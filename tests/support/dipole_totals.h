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

/// Total diffuse reflectance of the standard dipole, Jensen, Marschner, Levoy and Hanrahan 2001
/// (§2.4 and the BRDF approximation of §3.2, R_d = (α'/2)(1 + e^{−(4/3)A√(3(1−α'))}) e^{−√(3(1−α'))}),
/// with A = (1 + F_dr)/(1 − F_dr) and F_dr = −1.440/η² + 0.710/η + 0.668 + 0.0636η (their Eq. 4's
/// fit; the project clamps η to [1, 2.5] for it, which the materials used here satisfy).
inline double jensenTotalRd(double sigma_a, double sigma_s, double g, double eta) {
  const double sp = sigma_s * (1.0 - g);
  const double alphaP = sp / (sigma_a + sp);
  const double fdr = -1.440 / (eta * eta) + 0.710 / eta + 0.668 + 0.0636 * eta;
  const double A = (1.0 + fdr) / (1.0 - fdr);
  const double s = std::sqrt(3.0 * (1.0 - alphaP));
  return 0.5 * alphaP * (1.0 + std::exp(-4.0 / 3.0 * A * s)) * std::exp(-s);
}

}  // namespace tallow::test
