#pragma once
// The Monte Carlo estimator of scattered radiosity (Dal Corso et al., radiosity maps, Eq. 9) on the
// CPU: the C++ face of shaders/maps/estimator.glsl (the per-sample pieces: random numbers, Eq. 12
// sampling, x_j, Eqs. 13–14, the term of Eq. 9, Halton camera directions) and of
// shaders/maps/gather_loop.glsl (the loops over lights and samples), which the map passes compile
// as GLSL; here they run in float or double by the same lines, with the light G-buffers given as
// look-up functions. Formulas: docs/radiosity-maps.md, "The estimator".
// No OpenGL here.
#include <glm/glm.hpp>

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

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

/// What a light G-buffer texel saw: the surface point [mm] and its outward normal. The gather puts
/// x_i on the texel's tangent plane along the look-up line (texelPlane), as on the GPU.
struct LightGBufferHit {
  glm::dvec3 xi, ni;
};
/// A directional light's G-buffer: the texel over x_j [mm], or nothing (no surface of x_o's object
/// there: the sample contributes 0).
using LightGBufferLookup = std::function<std::optional<LightGBufferHit>(const glm::dvec3& xj)>;
/// A point light's cube G-buffer: the texel in `direction` (not unit) from the light, or nothing.
using PointGBufferLookup = std::function<std::optional<LightGBufferHit>(const glm::dvec3& direction)>;

struct GatherPointLight {
  glm::dvec3 position{0.0};   ///< x_ℓ [mm]
  glm::dvec3 intensity{0.0};  ///< I per band [W/sr]
  PointGBufferLookup lookup;
};

struct ScatteredRadiosityInput {
  glm::dvec3 xo{0.0}, no{0.0, 0.0, 1.0};  ///< the point of emergence [mm] and its outward normal
  RadiosityMaterial material;
  BssrdfModel model = BssrdfModel::Directional;
  int samples = 1;  ///< N, shared by the three bands (sssDrawSharedSample)
  /// The random stream: texel (x, y) of map k at accumulated frame F (the sample is looped).
  std::uint32_t texelX = 0, texelY = 0, map = 0, frame = 0;
  /// The directional light, looked up by the `lookup` argument; `directional` = false leaves it out.
  bool directional = true;
  glm::dvec3 toLight{0.0, 0.0, 1.0};  ///< unit, toward the directional light (= −ω_ℓ)
  glm::dvec3 irradiance{1.0};         ///< E per band [W/m²] on a surface facing the light (= L_ℓ)
  /// Orthonormal basis of the light's view plane (the directional light's sampling plane).
  glm::dvec3 t1{1.0, 0.0, 0.0}, t2{0.0, 1.0, 0.0};
  /// Point lights, each with its cube G-buffer (samples on x_o's tangent plane).
  std::vector<GatherPointLight> pointLights;
  /// The gather's settings, as sss.* on the GPU: sss.stereographic, sss.projected_area,
  /// sss.texel_plane, and sss.point_share (the second density's share: point lights, and a
  /// directional light where x_o is backlit; 0: Eq. 12 alone).
  bool stereographic = true, projectedArea = true, texelPlane = true;
  double pointShare = 0.0;
};

struct ScatteredRadiosity {
  glm::dvec3 B{0.0};              ///< B_N per band (Eq. 9) [W/m²]
  glm::dvec3 standardError{0.0};  ///< the sample standard deviation of the N terms × π E/N, per band
};

/// B_N(x_o) of Eq. 9 per colour band from every light of `input`, computed by the GPU's own loops
/// (shaders/maps/gather_loop.glsl, compiled here in float or double: Real): sample j is drawn once
/// for the three bands (sssDrawSharedSample), looked up once, and each band adds its term with the
/// mixture's weight; the projected-area ratio, the stereographic look-up and x_i on the texel's
/// plane as the settings say. The directional light's G-buffer is `lookup`. The standard error adds
/// the lights' variances as if independent (exact for one light). Throws std::invalid_argument for
/// samples < 1, or where validateBssrdfConfig rejects a band's (x_o, n_o, toLight, material):
/// non-unit n_o or toLight, invalid coefficients or η.
template <class Real>
ScatteredRadiosity estimateScatteredRadiosity(const ScatteredRadiosityInput& input, const LightGBufferLookup& lookup);
extern template ScatteredRadiosity estimateScatteredRadiosity<float>(const ScatteredRadiosityInput&,
                                                                     const LightGBufferLookup&);
extern template ScatteredRadiosity estimateScatteredRadiosity<double>(const ScatteredRadiosityInput&,
                                                                      const LightGBufferLookup&);

}  // namespace tallow::sss
