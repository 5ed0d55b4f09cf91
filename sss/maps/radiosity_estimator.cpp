#include "sss/maps/radiosity_estimator.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "gpu/glsl_shared.h"  // TALLOW_FN and GLM's GLSL vocabulary; no OpenGL

// The shared files, compiled once per precision as in sss/bssrdf.cpp. Besides real.glsl's types,
// the estimator needs GLSL's `uint`: std::uint32_t, whose arithmetic wraps modulo 2³² as GLSL's does.
static_assert(sizeof(unsigned) == 4, "GLSL uint literals (123u) must be 32-bit unsigned int in C++");

namespace tallow::sss::estimator_f32 {
using uint = std::uint32_t;
using real = float;
#include "gpu/glsl_real_types.inc"
#include "sss/bssrdf/bssrdf_models.inc"
#include "shaders/maps/estimator.glsl"
}  // namespace tallow::sss::estimator_f32

namespace tallow::sss::estimator_f64 {
using uint = std::uint32_t;
using real = double;
#include "gpu/glsl_real_types.inc"
#include "sss/bssrdf/bssrdf_models.inc"
#include "shaders/maps/estimator.glsl"
}  // namespace tallow::sss::estimator_f64

namespace tallow::sss {

static_assert(static_cast<int>(BssrdfModel::Standard) == estimator_f64::BSSRDF_MODEL_STANDARD);
static_assert(static_cast<int>(BssrdfModel::Directional) == estimator_f64::BSSRDF_MODEL_DIRECTIONAL);
static_assert(static_cast<int>(BssrdfModel::PhotonBeamDiffusion) == estimator_f64::BSSRDF_MODEL_PBD);

namespace {

/// The types and the namespace of one instantiation.
template <class Real>
struct Shared;
template <>
struct Shared<float> {
  using Vec = glm::vec3;
  using Sample = estimator_f32::SssSample;
  template <class F>
  static decltype(auto) call(F&& f) {
    namespace s = estimator_f32;
    return f(s::BssrdfCoefficients{}, [](auto&&... a) { return s::bssrdfCoefficients(a...); },
             [](auto&&... a) { return s::sssSamplingSigmaTr(a...); },
             [](auto&&... a) { return s::sssDrawSample(a...); },
             [](auto&&... a) { return s::sssDrawSharedSample(a...); },
             [](auto&&... a) { return s::sssRadiosityTerm(a...); },
             [](auto&&... a) { return s::sssRadiosityFromSum(a...); });
  }
};
template <>
struct Shared<double> {
  using Vec = glm::dvec3;
  using Sample = estimator_f64::SssSample;
  template <class F>
  static decltype(auto) call(F&& f) {
    namespace s = estimator_f64;
    return f(s::BssrdfCoefficients{}, [](auto&&... a) { return s::bssrdfCoefficients(a...); },
             [](auto&&... a) { return s::sssSamplingSigmaTr(a...); },
             [](auto&&... a) { return s::sssDrawSample(a...); },
             [](auto&&... a) { return s::sssDrawSharedSample(a...); },
             [](auto&&... a) { return s::sssRadiosityTerm(a...); },
             [](auto&&... a) { return s::sssRadiosityFromSum(a...); });
  }
};

}  // namespace

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
    BssrdfConfig check{in.xo, in.no, in.toLight, in.xo, in.no, m.sigma_a[c], m.sigma_s[c], m.g[c], m.eta};
    validateBssrdfConfig(check);
  }
  using Vec = typename Shared<Real>::Vec;
  return Shared<Real>::call([&](auto, auto coefficients, auto samplingSigmaTr, auto drawSample, auto drawShared,
                                auto term, auto fromSum) {
    const Vec xo(in.xo), no(in.no), wl(in.toLight), t1(in.t1), t2(in.t2);
    using K = decltype(coefficients(Real(0), Real(0), Real(0), Real(0)));
    std::array<K, 3> k;
    Vec sigmaTr;
    for (int c = 0; c < 3; ++c) {
      k[c] = coefficients(Real(m.sigma_a[c]), Real(m.sigma_s[c]), Real(m.g[c]), Real(m.eta));
      sigmaTr[c] = samplingSigmaTr(k[c]);
    }
    glm::dvec3 sum(0.0), sumSquares(0.0);
    const auto add = [&](int c, const typename Shared<Real>::Sample& s, const LightGBufferHit& hit) {
      const double t = static_cast<double>(
          term(static_cast<int>(in.model), Vec(hit.xi), Vec(hit.ni), wl, xo, no, k[c], s.weight));
      sum[c] += t;
      sumSquares[c] += t * t;
    };
    const auto n = static_cast<std::uint32_t>(in.samples);
    if (in.bandSampling == BandSampling::Shared) {
      // A directional light: a second density only where x_o lies behind the lit surface.
      double radius = 0.0;
      if (in.backlitShare > 0.0)
        if (const std::optional<LightGBufferHit> front = lookup(in.xo))
          radius = backlitRadius(glm::dot(front->xi - in.xo, in.toLight),
                                 static_cast<double>(std::min({sigmaTr.x, sigmaTr.y, sigmaTr.z})));
      const Real share = Real(radius > 0.0 ? in.backlitShare : 0.0);
      for (std::uint32_t j = 0; j < n; ++j) {
        const auto s = drawShared(xo, t1, t2, sigmaTr, Real(radius), share, in.texelX, in.texelY, in.map, in.frame, j, n);
        if (const std::optional<LightGBufferHit> hit = lookup(glm::dvec3(s.xj)))
          for (int c = 0; c < 3; ++c) add(c, s, *hit);
      }
    } else {
      for (int c = 0; c < 3; ++c)
        for (std::uint32_t j = 0; j < n; ++j) {
          const auto s = drawSample(xo, t1, t2, sigmaTr[c], in.texelX, in.texelY, in.map, in.frame,
                                    static_cast<std::uint32_t>(c), j);
          if (const std::optional<LightGBufferHit> hit = lookup(glm::dvec3(s.xj))) add(c, s, *hit);
        }
    }
    ScatteredRadiosity out;
    for (int c = 0; c < 3; ++c) {
      const double scale = static_cast<double>(fromSum(Real(1), Real(in.irradiance[c]), 1));  // π E
      out.B[c] = static_cast<double>(fromSum(Real(sum[c]), Real(in.irradiance[c]), in.samples));
      const double variance = n > 1 ? std::max(0.0, (sumSquares[c] - sum[c] * sum[c] / n) / (n - 1)) : 0.0;
      out.standardError[c] = scale * std::sqrt(variance / n);
    }
    return out;
  });
}
template ScatteredRadiosity estimateScatteredRadiosity<float>(const ScatteredRadiosityInput&,
                                                              const LightGBufferLookup&);
template ScatteredRadiosity estimateScatteredRadiosity<double>(const ScatteredRadiosityInput&,
                                                               const LightGBufferLookup&);

}  // namespace tallow::sss
