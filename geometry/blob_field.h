#pragma once
// The animated blob of the radiosity-maps paper (§4): Φ_t(p) = Σᵢ exp(−σ‖p − pᵢ(t)‖²) over four
// blobs moving on periodic Lissajous paths with different periods, so that the aggregate repeats
// only after the least common multiple of the periods. Exposed as iso − Φ_t (negative inside).
// value() and gradient() evaluate shaders/fields/blob.glsl, the lines the GPU evaluates from the
// same centres, σ, iso and scale (GpuBlobField).
#include "geometry/scalar_field.h"

#include <array>

namespace tallow::geometry {

struct BlobParams {
  static constexpr int kBlobCount = 4;  ///< the paper's "4 blobs"
  /// Gaussian falloff σ in 1/unit² of the blob's own (unscaled) space. With iso = 0.5 a lone blob
  /// has radius √(ln 2 / σ) ≈ 0.42 and two blobs join when their centres are closer than
  /// 2√(ln(2/iso) / σ) ≈ 1.18, so paths of amplitude ~1 make them merge and split.
  double sigma = 4.0;
  /// Isovalue of Φ_t; the surface is Φ_t = iso. In (0, kBlobCount).
  double iso = 0.5;
  /// Half-extent of every Lissajous path along x, y, z (unscaled units).
  glm::dvec3 amplitude{1.0, 0.8, 0.8};
  /// Period of each blob's path in seconds; pairwise coprime so the whole shape repeats only
  /// every 5·7·11·13 = 5005 s (the paper's point: no precomputation over a period).
  std::array<double, kBlobCount> period{5.0, 7.0, 11.0, 13.0};
  /// Lissajous frequency multiples (x, y, z) of each path; all start at the origin at t = 0,
  /// where the four blobs form one merged ball.
  std::array<glm::dvec3, kBlobCount> frequency{glm::dvec3(1, 2, 3), glm::dvec3(3, 1, 2),
                                               glm::dvec3(2, 3, 1), glm::dvec3(1, 3, 2)};
  /// Metres per unscaled unit: with the defaults the blob spans about 0.1 m.
  double scale = 0.03;
};

class BlobField final : public ScalarField {
 public:
  /// The field at time t (seconds); deterministic: the same t always gives the same field.
  explicit BlobField(double t, const BlobParams& params = {});

  double value(glm::dvec3 p) const override;     ///< iso − Φ_t(p / scale)
  glm::dvec3 gradient(glm::dvec3 p) const override;  ///< analytic, world units (1/m)
  Aabb bounds() const override;                  ///< contains the surface at every t

  /// Centre pᵢ(t) of blob i in world units (metres).
  glm::dvec3 centre(int i) const { return centres_[static_cast<std::size_t>(i)] * params_.scale; }
  /// Centre pᵢ(t) in the blob's unscaled units (what shaders/fields/blob.glsl takes).
  glm::dvec3 unscaledCentre(int i) const { return centres_[static_cast<std::size_t>(i)]; }
  const BlobParams& params() const { return params_; }
  double time() const { return t_; }

 private:
  BlobParams params_;
  double t_;
  std::array<glm::dvec3, BlobParams::kBlobCount> centres_;  ///< unscaled units
};

}  // namespace tallow::geometry
