#include "geometry/blob_field.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "gpu/glsl_shared.h"  // TALLOW_FN and GLM's GLSL vocabulary; no OpenGL

// Φ_t and its gradient: the lines the GPU evaluates (shaders/fields/blob.glsl), compiled here in
// double, the precision the CPU mesher, `tallow field` and the reference integrator have always used.
namespace tallow::geometry::blob_f64 {
using real = double;
#include "gpu/glsl_real_types.inc"
#include "shaders/fields/blob.glsl"
}  // namespace tallow::geometry::blob_f64

namespace tallow::geometry {

static_assert(blob_f64::BLOB_COUNT == BlobParams::kBlobCount, "shaders/fields/blob.glsl's blob count");

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
  return blob_f64::blobFieldValue(p, centres_.data(), params_.sigma, params_.iso, params_.scale);
}

glm::dvec3 BlobField::gradient(glm::dvec3 p) const {
  return blob_f64::blobFieldGradient(p, centres_.data(), params_.sigma, params_.scale);
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
