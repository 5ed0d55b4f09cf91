#pragma once
// The Monte Carlo estimator of scattered radiosity (Dal Corso et al., radiosity maps, Eq. 9) on the
// CPU: the C++ face of shaders/maps/estimator.glsl, which the scattered-radiosity map pass compiles
// as GLSL. The per-sample logic (random numbers, Eq. 12 sampling, x_j, Eqs. 13–14, the term of
// Eq. 9, Halton camera directions) lives in that file and runs here in float or double by the same
// lines; this side only loops over the samples. Formulas: docs/radiosity-maps.md, "The estimator".
// No OpenGL here.
#include <glm/glm.hpp>

#include <cstdint>
#include <functional>
#include <optional>

#include "sss/bssrdf/bssrdf.h"

namespace tallow::sss {

/// The random stream of one number: texel (x, y) of map k, accumulated frame F, colour band c,
/// sample j, and which number of the sample (dim 0: ξ1 for r, 1: ξ2 for α, 2: the pick of density
/// of the shared pattern).
struct RandomStreamId {
  std::uint32_t x = 0, y = 0, map = 0, frame = 0, band = 0, sample = 0, dim = 0;
};

/// The 32-bit counter hash behind ξ (PCG hash; identical bits on the GPU).
std::uint32_t radiosityRandomBits(const RandomStreamId& id);
/// ξ ∈ [0, 1), a multiple of 2⁻²⁴, from the float (Real = float) or the double instantiation of the
/// shared code; both give the same value exactly.
template <class Real>
Real radiosityRandom(const RandomStreamId& id);
extern template float radiosityRandom<float>(const RandomStreamId&);
extern template double radiosityRandom<double>(const RandomStreamId&);

/// Radical inverse Φ_base(i) (Halton 1964).
double radicalInverse(std::uint32_t i, std::uint32_t base);
/// The k-th (k ≥ 0) of the map-camera directions: (Φ₂(k+1), Φ₃(k+1)) mapped uniformly to the unit
/// sphere (z = 1 − 2u, φ = 2πv).
template <class Real>
glm::dvec3 haltonDirection(std::uint32_t k);
extern template glm::dvec3 haltonDirection<float>(std::uint32_t);
extern template glm::dvec3 haltonDirection<double>(std::uint32_t);

/// The cube-map look-up direction x_stereo − x_ℓ of the stereographic correction (Eqs. 13–14), for
/// the sampled point x_j in the tangent plane of x_o and a point light at x_ℓ; and the planar one,
/// x_j − x_ℓ.
template <class Real>
glm::dvec3 stereographicLookupDirection(const glm::dvec3& xo, const glm::dvec3& xj, const glm::dvec3& xl);
extern template glm::dvec3 stereographicLookupDirection<float>(const glm::dvec3&, const glm::dvec3&, const glm::dvec3&);
extern template glm::dvec3 stereographicLookupDirection<double>(const glm::dvec3&, const glm::dvec3&,
                                                                 const glm::dvec3&);
glm::dvec3 planarLookupDirection(const glm::dvec3& xj, const glm::dvec3& xl);

/// dA_i/dA_j for a point light at x_l: the surface area at x_i [its normal n_i] per area of x_o's
/// tangent plane [normal n_o] at the sample x_j, through the planar or the stereographic (Eqs.
/// 13–14) look-up (sss.projected_area; formulas in shaders/maps/estimator.glsl).
double planarAreaRatio(const glm::dvec3& no, const glm::dvec3& xj, const glm::dvec3& xl, const glm::dvec3& xi,
                       const glm::dvec3& ni);
double stereographicAreaRatio(const glm::dvec3& xo, const glm::dvec3& no, const glm::dvec3& xj, const glm::dvec3& xl,
                              const glm::dvec3& xi, const glm::dvec3& ni);

/// x_i from the light G-buffer texel the look-up line origin + t·d (d unit) falls in, whose centre
/// saw the surface point p with normal n: on the texel's tangent plane when onPlane (and the line
/// is not grazing it), else at the texel's depth along the line (sss.texel_plane).
template <class Real>
glm::dvec3 pointOnTexel(const glm::dvec3& origin, const glm::dvec3& d, const glm::dvec3& p, const glm::dvec3& n,
                        bool onPlane);
extern template glm::dvec3 pointOnTexel<float>(const glm::dvec3&, const glm::dvec3&, const glm::dvec3&,
                                               const glm::dvec3&, bool);
extern template glm::dvec3 pointOnTexel<double>(const glm::dvec3&, const glm::dvec3&, const glm::dvec3&,
                                                const glm::dvec3&, bool);

/// The rate of the exponential distance distribution (Eq. 12) of one band [mm⁻¹]: σ_tr (Eq. 10),
/// bounded below by 10⁻³ σ_t' and 10⁻⁶ mm⁻¹ so that σ_a = 0 samples finite distances.
double samplingSigmaTr(double sigma_a, double sigma_s, double g, double eta);

/// Point lights' second distance density (issue 17; shaders/maps/estimator.glsl): the stereographic
/// image of uniform directions about a light at distance R = radius [mm] from x_o, per (r, α) as
/// Eq. 11 is written: p₂(r, α) = r (1 + r²/4R²)⁻²/(4πR²).
double stereoRadialPdf(double r, double radius);
/// r of p₂ from ξ ∈ [0, 1): 2R √(ξ/(1 − ξ)).
double sampleStereoRadius(double xi, double radius);
/// p_mix(r, α) [per mm per radian] of the sample pattern the three colour bands share (issue 17;
/// shaders/maps/estimator.glsl): (1 − share)·(the bands' Eq. 11 at their rates sigmaTr, averaged) +
/// share·p₂ about a light at distance radius. The weight of a drawn r is r/p_mix.
double bandMixturePdf(double r, const glm::dvec3& sigmaTr, double radius, double share);
/// R of the second density for a directional light where x_o lies `depth` [mm] behind the lit
/// surface (shaders/maps/estimator.glsl, sssBacklitRadius): 0 where depth·σ_tr,min ≤ 1.
double backlitRadius(double depth, double sigmaTrMin);

/// Sample `stream.sample` of `sampleCount` on x_o's tangent plane (orthonormal t1, t2) as the gather
/// draws it for all three bands at once: the technique (p₂ with probability share when radius > 0,
/// else band c's Eq. 12 with probability (1 − share)/3) picked by fract(ξ₀ + sample/sampleCount), ξ₀
/// from dimension 2 of sample 0; stream (texelX, texelY, map, frame, SSS_SHARED_BAND = 3, sample)
/// — stream.band is ignored.
struct PlanarSample {
  glm::dvec3 xj{0.0};
  double r = 0.0, alpha = 0.0, weight = 0.0;  ///< weight = r/p(r, α) [mm²]
};
template <class Real>
PlanarSample drawSharedSample(const glm::dvec3& xo, const glm::dvec3& t1, const glm::dvec3& t2,
                              const glm::dvec3& sigmaTr, double radius, double share, const RandomStreamId& stream,
                              std::uint32_t sampleCount);
extern template PlanarSample drawSharedSample<float>(const glm::dvec3&, const glm::dvec3&, const glm::dvec3&,
                                                     const glm::dvec3&, double, double, const RandomStreamId&,
                                                     std::uint32_t);
extern template PlanarSample drawSharedSample<double>(const glm::dvec3&, const glm::dvec3&, const glm::dvec3&,
                                                      const glm::dvec3&, double, double, const RandomStreamId&,
                                                      std::uint32_t);

/// Optical properties per colour band (r, g, b) [mm⁻¹] and the relative index of refraction.
struct RadiosityMaterial {
  glm::dvec3 sigma_a{0.0}, sigma_s{0.0}, g{0.0};
  double eta = 1.3;
};

/// What the light's G-buffer holds at the texel x_j falls in: the surface point x_i [mm] and its
/// outward unit normal n_i.
struct LightGBufferHit {
  glm::dvec3 xi, ni;
};
/// x_j [mm] → the G-buffer entry, or nothing (no surface there: the sample contributes 0).
using LightGBufferLookup = std::function<std::optional<LightGBufferHit>(const glm::dvec3& xj)>;

/// How the three colour bands' samples are drawn: one pattern for all three (the gather's, issue
/// 17: sssDrawSharedSample, each band weighted by the mixture), or each band its own with its σ_tr
/// (the paper's §3.1: sssDrawSample, stream band c) — kept to measure against.
enum class BandSampling { Shared, PerBand };

struct ScatteredRadiosityInput {
  glm::dvec3 xo{0.0}, no{0.0, 0.0, 1.0};  ///< the point of emergence [mm] and its outward normal
  glm::dvec3 toLight{0.0, 0.0, 1.0};      ///< unit, toward the directional light (= −ω_ℓ)
  glm::dvec3 irradiance{1.0};             ///< E per band [W/m²] on a surface facing the light (= L_ℓ)
  RadiosityMaterial material;
  BssrdfModel model = BssrdfModel::Directional;
  int samples = 1;  ///< N per band (≥ 1); with BandSampling::Shared the bands share the N
  BandSampling bandSampling = BandSampling::Shared;
  /// The random stream: texel (x, y) of map k at accumulated frame F (band and sample are looped).
  std::uint32_t texelX = 0, texelY = 0, map = 0, frame = 0;
  /// Orthonormal basis of the sampling plane (the light's view plane for a directional light).
  glm::dvec3 t1{1.0, 0.0, 0.0}, t2{0.0, 1.0, 0.0};
  /// Shared pattern: the second density's share where x_o is backlit (sss.point_share, as the
  /// gather): the depth of lookup(x_o) ahead of x_o along toLight gives sssBacklitRadius; 0: Eq. 12 alone.
  double backlitShare = 0.0;
};

struct ScatteredRadiosity {
  glm::dvec3 B{0.0};              ///< B_N per band (Eq. 9) [W/m²]
  glm::dvec3 standardError{0.0};  ///< the sample standard deviation of the N terms × π E/N, per band
};

/// B_N(x_o) = (π E/N) Σ_j S_d(x_i, −ω_ℓ; x_o) F_t(−ω_ℓ) cos θ_ℓ r_j/p(r_j, α_j)   (Eq. 9)
/// for each colour band c. BandSampling::Shared (as the gather): sample j is drawn once for the three
/// bands by drawSharedSample (directional light: share 0), looked up once, and each band adds its
/// term with the mixture's weight. BandSampling::PerBand (§3.1): sample j of band c draws (r, α) of
/// Eq. 12 with band c's σ_tr from stream (texelX, texelY, map, frame, c, j). Either way
/// x_j = x_o + r(cos α t1 + sin α t2), (x_i, n_i) = lookup(x_j), and the term is the shared code's
/// (0 on a miss or where n_i faces away from the light). Real selects the instantiation of the shared code. Throws
/// std::invalid_argument for samples < 1, or where validateBssrdfConfig rejects a band's
/// (x_o, n_o, toLight, material): non-unit n_o or toLight, invalid coefficients or η.
template <class Real>
ScatteredRadiosity estimateScatteredRadiosity(const ScatteredRadiosityInput& input, const LightGBufferLookup& lookup);
extern template ScatteredRadiosity estimateScatteredRadiosity<float>(const ScatteredRadiosityInput&,
                                                                     const LightGBufferLookup&);
extern template ScatteredRadiosity estimateScatteredRadiosity<double>(const ScatteredRadiosityInput&,
                                                                      const LightGBufferLookup&);

}  // namespace tallow::sss
