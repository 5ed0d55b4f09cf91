#include "sss/maps/radiosity_estimator.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "gpu/glsl_shared.h"  // TALLOW_FN and GLM's GLSL vocabulary; no OpenGL

namespace tallow::sss {
/// What gather_loop.glsl's accessors read on the CPU (sss/maps/gather_scene_cpu.inc).
struct GatherSceneCpu {
  const ScatteredRadiosityInput* input;
  const LightGBufferLookup* directionalLookup;
};
}  // namespace tallow::sss

// The shared files, compiled once per precision as in sss/bssrdf.cpp. Besides real.glsl's types,
// the estimator needs GLSL's `uint`: std::uint32_t, whose arithmetic wraps modulo 2³² as GLSL's does.
static_assert(sizeof(unsigned) == 4, "GLSL uint literals (123u) must be 32-bit unsigned int in C++");

namespace tallow::sss::estimator_f32 {
using uint = std::uint32_t;
using real = float;
#include "gpu/glsl_real_types.inc"
#include "sss/bssrdf/bssrdf_models.inc"
#include "shaders/maps/estimator.glsl"
#include "sss/maps/gather_scene_cpu.inc"
}  // namespace tallow::sss::estimator_f32

namespace tallow::sss::estimator_f64 {
using uint = std::uint32_t;
using real = double;
#include "gpu/glsl_real_types.inc"
#include "sss/bssrdf/bssrdf_models.inc"
#include "shaders/maps/estimator.glsl"
#include "sss/maps/gather_scene_cpu.inc"
}  // namespace tallow::sss::estimator_f64

namespace tallow::sss {

static_assert(static_cast<int>(BssrdfModel::Standard) == estimator_f64::BSSRDF_MODEL_STANDARD);
static_assert(static_cast<int>(BssrdfModel::Directional) == estimator_f64::BSSRDF_MODEL_DIRECTIONAL);
static_assert(static_cast<int>(BssrdfModel::PhotonBeamDiffusion) == estimator_f64::BSSRDF_MODEL_PBD);

std::uint32_t radiosityRandomBits(const RandomStreamId& id) {
  return estimator_f64::sssRandomBits(id.x, id.y, id.map, id.frame, id.band, id.sample, id.dim);
}

template <class Real>
Real radiosityRandom(const RandomStreamId& id) {
  if constexpr (std::is_same_v<Real, float>)
    return estimator_f32::sssRandom(id.x, id.y, id.map, id.frame, id.band, id.sample, id.dim);
  else
    return estimator_f64::sssRandom(id.x, id.y, id.map, id.frame, id.band, id.sample, id.dim);
}
template float radiosityRandom<float>(const RandomStreamId&);
template double radiosityRandom<double>(const RandomStreamId&);

double radicalInverse(std::uint32_t i, std::uint32_t base) {
  if (base < 2) throw std::invalid_argument("radicalInverse: base must be at least 2");
  return estimator_f64::sssRadicalInverse(i, base);
}

template <class Real>
glm::dvec3 haltonDirection(std::uint32_t k) {
  if constexpr (std::is_same_v<Real, float>)
    return glm::dvec3(estimator_f32::sssHaltonDirection(k));
  else
    return estimator_f64::sssHaltonDirection(k);
}
template glm::dvec3 haltonDirection<float>(std::uint32_t);
template glm::dvec3 haltonDirection<double>(std::uint32_t);

template <class Real>
glm::dvec3 stereographicLookupDirection(const glm::dvec3& xo, const glm::dvec3& xj, const glm::dvec3& xl) {
  if constexpr (std::is_same_v<Real, float>)
    return glm::dvec3(estimator_f32::sssStereographicLookupDirection(glm::vec3(xo), glm::vec3(xj), glm::vec3(xl)));
  else
    return estimator_f64::sssStereographicLookupDirection(xo, xj, xl);
}
template glm::dvec3 stereographicLookupDirection<float>(const glm::dvec3&, const glm::dvec3&, const glm::dvec3&);
template glm::dvec3 stereographicLookupDirection<double>(const glm::dvec3&, const glm::dvec3&, const glm::dvec3&);

glm::dvec3 planarLookupDirection(const glm::dvec3& xj, const glm::dvec3& xl) {
  return estimator_f64::sssPlanarLookupDirection(xj, xl);
}

template <class Real>
glm::dvec3 pointOnTexel(const glm::dvec3& origin, const glm::dvec3& d, const glm::dvec3& p, const glm::dvec3& n,
                        bool onPlane) {
  if constexpr (std::is_same_v<Real, float>)
    return glm::dvec3(estimator_f32::sssPointOnTexel(glm::vec3(origin), glm::vec3(d), glm::vec3(p), glm::vec3(n),
                                                     onPlane ? 1 : 0));
  else
    return estimator_f64::sssPointOnTexel(origin, d, p, n, onPlane ? 1 : 0);
}
template glm::dvec3 pointOnTexel<float>(const glm::dvec3&, const glm::dvec3&, const glm::dvec3&, const glm::dvec3&,
                                        bool);
template glm::dvec3 pointOnTexel<double>(const glm::dvec3&, const glm::dvec3&, const glm::dvec3&, const glm::dvec3&,
                                         bool);

double planarAreaRatio(const glm::dvec3& no, const glm::dvec3& xj, const glm::dvec3& xl, const glm::dvec3& xi,
                       const glm::dvec3& ni) {
  return estimator_f64::sssPlanarAreaRatio(no, xj, xl, xi, ni);
}
double stereographicAreaRatio(const glm::dvec3& xo, const glm::dvec3& no, const glm::dvec3& xj, const glm::dvec3& xl,
                              const glm::dvec3& xi, const glm::dvec3& ni) {
  return estimator_f64::sssStereographicAreaRatio(xo, no, xj, xl, xi, ni);
}

double backlitRadius(double depth, double sigmaTrMin) { return estimator_f64::sssBacklitRadius(depth, sigmaTrMin); }
double stereoRadialPdf(double r, double radius) { return estimator_f64::sssStereoRadialPdf(r, radius); }
double sampleStereoRadius(double xi, double radius) { return estimator_f64::sssSampleStereoRadius(xi, radius); }
double bandMixturePdf(double r, const glm::dvec3& sigmaTr, double radius, double share) {
  return estimator_f64::sssBandMixturePdf(r, sigmaTr, radius, share);
}

template <class Real>
PlanarSample drawSharedSample(const glm::dvec3& xo, const glm::dvec3& t1, const glm::dvec3& t2,
                              const glm::dvec3& sigmaTr, double radius, double share, const RandomStreamId& id,
                              std::uint32_t sampleCount) {
  const auto draw = [&](auto ns, auto vec) {
    using V = decltype(vec);
    using R = typename V::value_type;
    const auto s = ns(V(xo), V(t1), V(t2), V(sigmaTr), R(radius), R(share), id.x, id.y, id.map, id.frame, id.sample,
                      sampleCount);
    return PlanarSample{glm::dvec3(s.xj), double(s.r), double(s.alpha), double(s.weight)};
  };
  if constexpr (std::is_same_v<Real, float>)
    return draw([](auto&&... a) { return estimator_f32::sssDrawSharedSample(a...); }, glm::vec3());
  else
    return draw([](auto&&... a) { return estimator_f64::sssDrawSharedSample(a...); }, glm::dvec3());
}
template PlanarSample drawSharedSample<float>(const glm::dvec3&, const glm::dvec3&, const glm::dvec3&,
                                              const glm::dvec3&, double, double, const RandomStreamId&,
                                              std::uint32_t);
template PlanarSample drawSharedSample<double>(const glm::dvec3&, const glm::dvec3&, const glm::dvec3&,
                                               const glm::dvec3&, double, double, const RandomStreamId&,
                                               std::uint32_t);

double samplingSigmaTr(double sigma_a, double sigma_s, double g, double eta) {
  return estimator_f64::sssSamplingSigmaTr(estimator_f64::bssrdfCoefficients(sigma_a, sigma_s, g, eta));
}

template <class Real>
ScatteredRadiosity estimateScatteredRadiosity(const ScatteredRadiosityInput& in, const LightGBufferLookup& lookup) {
  if (in.samples < 1)
    throw std::invalid_argument("estimateScatteredRadiosity: samples must be at least 1 (" +
                                std::to_string(in.samples) + ")");
  const RadiosityMaterial& m = in.material;
  for (int c = 0; c < 3; ++c) {
    BssrdfConfig check{in.xo, in.no, in.directional ? in.toLight : in.no, in.xo, in.no, m.sigma_a[c], m.sigma_s[c],
                       m.g[c], m.eta};
    validateBssrdfConfig(check);
  }
  for (const GatherPointLight& l : in.pointLights)
    if (!l.lookup) throw std::invalid_argument("estimateScatteredRadiosity: a point light has no G-buffer look-up");
  const GatherSceneCpu scene{&in, &lookup};
  if constexpr (std::is_same_v<Real, float>)
    return estimator_f32::sssEstimateOnCpu(scene);
  else
    return estimator_f64::sssEstimateOnCpu(scene);
}
template ScatteredRadiosity estimateScatteredRadiosity<float>(const ScatteredRadiosityInput&,
                                                              const LightGBufferLookup&);
template ScatteredRadiosity estimateScatteredRadiosity<double>(const ScatteredRadiosityInput&,
                                                               const LightGBufferLookup&);

}  // namespace tallow::sss
