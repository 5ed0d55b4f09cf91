#include "geometry/blob_field.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace tallow::geometry {

BlobField::BlobField(double t, const BlobParams& params) : params_(params), t_(t) {
  if (!(params_.sigma > 0.0) || !(params_.iso > 0.0) || !(params_.iso < BlobParams::kBlobCount) ||
      !(params_.scale > 0.0))
    throw std::invalid_argument("BlobParams: need sigma > 0, 0 < iso < 4, scale > 0");
  for (std::size_t i = 0; i < centres_.size(); ++i) {
    if (!(params_.period[i] > 0.0)) throw std::invalid_argument("BlobParams: periods must be > 0");
    // Reduce t modulo the period first so that large t keeps full precision and t, t + T give
    // bit-identical fields.
    const double phase = 2.0 * std::numbers::pi * (std::fmod(t, params_.period[i]) / params_.period[i]);
    const glm::dvec3 f = params_.frequency[i];
    centres_[i] = params_.amplitude *
                  glm::dvec3(std::sin(f.x * phase), std::sin(f.y * phase), std::sin(f.z * phase));
  }
}

double BlobField::value(glm::dvec3 p) const {
  const glm::dvec3 q = p / params_.scale;
  double phi = 0.0;
  for (const glm::dvec3& c : centres_) {
    const glm::dvec3 d = q - c;
    phi += std::exp(-params_.sigma * glm::dot(d, d));
  }
  return params_.iso - phi;
}

glm::dvec3 BlobField::gradient(glm::dvec3 p) const {
  // ∇_p (iso − Σ exp(−σ‖q − c‖²)) with q = p / scale: Σ 2σ (q − c) exp(…) / scale.
  const glm::dvec3 q = p / params_.scale;
  glm::dvec3 g(0.0);
  for (const glm::dvec3& c : centres_) {
    const glm::dvec3 d = q - c;
    g += (2.0 * params_.sigma * std::exp(-params_.sigma * glm::dot(d, d))) * d;
  }
  return g / params_.scale;
}

Aabb BlobField::bounds() const {
  // Farther than r from every centre, Φ < 4·exp(−σr²); with r = √(ln(4 / iso) / σ) that is < iso,
  // i.e. outside. Centres stay within ±amplitude, so this box holds the surface at every t.
  const double reach = std::sqrt(std::log(BlobParams::kBlobCount / params_.iso) / params_.sigma);
  const glm::dvec3 half = (params_.amplitude + reach) * params_.scale;
  Aabb box;
  box.extend(glm::vec3(-half));
  box.extend(glm::vec3(half));
  return box;
}

}  // namespace tallow::geometry
