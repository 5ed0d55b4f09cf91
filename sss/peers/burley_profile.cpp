#include "sss/peers/burley_profile.h"

#include "gpu/glsl_shared.h"  // TALLOW_FN and GLM's GLSL vocabulary; no OpenGL

// The shared profile file, in double (the GPU compiles the same lines in float).
namespace tallow::sss::burley_f64 {
using real = double;
#include "gpu/glsl_real_types.inc"
#include "shaders/bssrdf/real.glsl"
#include "shaders/bssrdf/fresnel.glsl"
#include "shaders/bssrdf/coefficients.glsl"
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

}  // namespace tallow::sss
