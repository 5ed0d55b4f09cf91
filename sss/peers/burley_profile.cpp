#include "sss/peers/burley_profile.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "gpu/glsl_shared.h"  // TALLOW_FN and GLM's GLSL vocabulary; no OpenGL

// The shared profile file, in double (the GPU compiles the same lines in float).
namespace tallow::sss::burley_f64 {
using real = double;
#include "gpu/glsl_real_types.inc"
#include "shaders/bssrdf/real.glsl"
#include "shaders/bssrdf/fresnel.glsl"
#include "shaders/bssrdf/coefficients.glsl"
#include "shaders/bssrdf/standard_dipole.glsl"
#include "shaders/peers/burley/profile.glsl"
}  // namespace tallow::sss::burley_f64

namespace tallow::sss {
namespace {

burley_f64::BurleyBand shared(const BurleyBandParams& b) {
  burley_f64::BurleyBand s;
  s.albedo = b.albedo;
  s.d = b.d;
  return s;
}

}  // namespace

std::array<BurleyBandParams, 3> burleyBands(const Material& m) {
  std::array<BurleyBandParams, 3> out;
  for (int c = 0; c < 3; ++c) {
    const burley_f64::BssrdfCoefficients k = burley_f64::bssrdfCoefficients(m.sigma_a[c], m.sigma_s[c], m.g[c], m.eta);
    const burley_f64::BurleyBand b = burley_f64::burleyBand(k);
    out[static_cast<std::size_t>(c)] = {b.albedo, b.d};
  }
  return out;
}

double burleyProfile(double r, const BurleyBandParams& band) { return burley_f64::burleyProfile(r, shared(band)); }
double burleyRadiusPdf(double r, double d) { return burley_f64::burleyRadiusPdf(r, d); }
double burleySampleRadius(double u1, double u2, double d) { return burley_f64::burleySampleRadius(u1, u2, d); }
double burleyTransmittance(double t, const BurleyBandParams& band) {
  return burley_f64::burleyTransmittance(t, shared(band));
}
double burleyScale(double albedo) { return burley_f64::burleyScale(albedo); }

double burleyHalfPlaneMass(double a, double d) {
  // ∫_a^∞ (R/A) 2r acos(a/r) dr with R/A = (e^{−r/d} + e^{−r/(3d)})/(8π d r): Simpson's rule in
  // u = log(r − a + ε) over the decades the exponentials span (60 d: e^{−20} of the slow one).
  const double lo = std::log(1e-9 * d), hi = std::log(60.0 * d);
  constexpr int kSteps = 2000;
  const double h = (hi - lo) / kSteps;
  double sum = 0.0;
  for (int i = 0; i <= kSteps; ++i) {
    const double x = std::exp(lo + i * h);  // r − a
    const double r = a + x;
    const double f = (std::exp(-r / d) + std::exp(-r / (3.0 * d))) / (8.0 * std::numbers::pi * d * r) * 2.0 * r *
                     std::acos(std::min(1.0, a / r)) * x;  // dr = x du
    sum += f * ((i == 0 || i == kSteps) ? 1.0 : (i % 2 ? 4.0 : 2.0));
  }
  return sum * h / 3.0;
}

std::vector<BurleyTap> burleySeparableTaps(const std::array<BurleyBandParams, 3>& bands, int halfTaps) {
  const int k = std::max(halfTaps, 1);
  const double dMax = std::max({bands[0].d, bands[1].d, bands[2].d});
  const double radius = kBurleySeparableRadius * dMax;
  std::vector<BurleyTap> taps(static_cast<std::size_t>(k) + 1);
  for (int i = 0; i <= k; ++i) taps[static_cast<std::size_t>(i)].offset = radius * (double(i) / k) * (double(i) / k);
  for (int c = 0; c < 3; ++c) {
    const double d = bands[static_cast<std::size_t>(c)].d;
    // The strip of tap i reaches from the midpoint to tap i − 1 to the midpoint to tap i + 1 (tap 0:
    // symmetric about 0; tap K: to infinity). Its mass: H(lower) − H(upper).
    double lowerMass = 0.5;  // H(0): the centre strip takes 2 (0.5 − H(m_1))
    for (int i = 0; i <= k; ++i) {
      const double upper = i == k ? -1.0 : 0.5 * (taps[static_cast<std::size_t>(i)].offset +
                                                   taps[static_cast<std::size_t>(i) + 1].offset);
      const double upperMass = upper < 0.0 ? 0.0 : burleyHalfPlaneMass(upper, d);
      const double mass = lowerMass - upperMass;
      taps[static_cast<std::size_t>(i)].weight[static_cast<std::size_t>(c)] = i == 0 ? 2.0 * mass : mass;
      lowerMass = upperMass;
    }
  }
  return taps;
}

}  // namespace tallow::sss
