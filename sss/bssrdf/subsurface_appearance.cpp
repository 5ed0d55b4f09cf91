#include "sss/bssrdf/subsurface_appearance.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "sss/bssrdf/bssrdf.h"

namespace tallow::sss {
namespace {

std::string bandText(int c) { return std::string(1, "rgb"[c]); }

}  // namespace

double reducedAlbedoFor(double reflectance, double eta) {
  if (!(reflectance >= 0.0 && reflectance <= 1.0))
    throw std::invalid_argument("subsurface_color: " + std::to_string(reflectance) + " is outside [0, 1]");
  double lo = 0.0, hi = 1.0;
  for (int i = 0; i < 64; ++i) {  // 2^-64: below double's resolution of [0, 1]
    const double mid = 0.5 * (lo + hi);
    (dipoleTotalReflectance(mid, eta) < reflectance ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

Material materialFromAppearance(const SubsurfaceAppearance& a) {
  if (!(a.radiusMm > 0.0f) || !std::isfinite(a.radiusMm))
    throw std::invalid_argument("subsurface_radius_mm: must be a positive number of millimetres");
  if (!(a.eta > 0.0f) || !std::isfinite(a.eta)) throw std::invalid_argument("eta: must be positive");
  Material m;
  m.name = "custom (subsurface colour)";
  m.eta = a.eta;
  m.g = a.g;
  for (int c = 0; c < 3; ++c) {
    if (!(a.radiusScale[c] > 0.0f) || !std::isfinite(a.radiusScale[c]))
      throw std::invalid_argument("subsurface_radius_scale: the " + bandText(c) + " band's must be positive");
    if (!(std::abs(a.g[c]) < 1.0f)) throw std::invalid_argument("g: |g| must be below 1");
    const double alphaP = reducedAlbedoFor(a.color[c], a.eta);
    const double sigmaTp = 1.0 / (static_cast<double>(a.radiusMm) * a.radiusScale[c]);  // [mm⁻¹]
    const double sigmaSp = alphaP * sigmaTp;
    m.sigma_a[c] = static_cast<float>(sigmaTp - sigmaSp);
    m.sigma_s[c] = static_cast<float>(sigmaSp / (1.0 - a.g[c]));
  }
  validateMaterial(m);
  return m;
}

SubsurfaceAppearance appearanceOf(const Material& m) {
  SubsurfaceAppearance a;
  a.eta = m.eta;
  a.g = m.g;
  glm::dvec3 ell;
  for (int c = 0; c < 3; ++c) {
    const double sigmaSp = static_cast<double>(m.sigma_s[c]) * (1.0 - m.g[c]);
    const double sigmaTp = m.sigma_a[c] + sigmaSp;
    a.color[c] = static_cast<float>(dipoleTotalReflectance(sigmaSp / sigmaTp, m.eta));
    ell[c] = 1.0 / sigmaTp;
  }
  const double longest = std::max({ell.x, ell.y, ell.z});
  a.radiusMm = static_cast<float>(longest);
  a.radiusScale = glm::vec3(ell / longest);
  return a;
}

}  // namespace tallow::sss
