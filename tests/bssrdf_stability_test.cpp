// Stability of the BSSRDF models on hard cases: 10⁷ configurations (random and adversarial, three
// models), each evaluated in float and in double, must all give finite values. The share of negative raw
// values (clamped to 0 by a renderer, directional-dipole paper §6.1) is reported per region:
// frontlit/backlit (μ0 = −n_o·ω12 > 0 or ≤ 0, Eq. 24) × near/far (|x_o − x_i| below or above one
// transport mean free path 1/σ_t').
//
// Counts: 4.8·10⁶ configurations each for the standard and the directional dipole and 4·10⁵ for
// photon beam diffusion (10⁷ in all), each evaluated in float and in double: 2·10⁷ evaluations. PBD gets
// fewer because one evaluation integrates along the beam (≈ 100–300 kernel evaluations, ~15 µs);
// its adversarial share is the same.
#include "sss/bssrdf/bssrdf.h"

#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <string>

#include "gpu/glsl_shared.h"

namespace tallow::bssrdf_stability_shared {
using namespace glm;
using real = double;
using real2 = glm::dvec2;
using real3 = glm::dvec3;
#include "shaders/bssrdf/real.glsl"
#include "shaders/bssrdf/fresnel.glsl"
}  // namespace tallow::bssrdf_stability_shared

namespace tallow::sss {
namespace {

using glm::dvec3;

constexpr std::array<BssrdfModel, 3> kModels = {BssrdfModel::Standard, BssrdfModel::Directional,
                                                BssrdfModel::PhotonBeamDiffusion};
constexpr std::array<long, 3> kConfigsPerModel = {4'800'000, 4'800'000, 400'000};

/// The kinds of configuration drawn, in turn. Everything random is drawn log-uniformly where the
/// scale matters: lengths 1e-6–1e4 mm, σ_a, σ_s 1e-4–1e3 mm⁻¹.
enum Kind {
  kRandom,              // all of it random, η ∈ [0.5, 2.5], g ∈ (−0.99, 0.99)
  kPlanar,              // x_o on the tangent plane, n_o = n_i (the configuration the models are built for)
  kCoincident,          // x_o = x_i
  kAlongNormal,         // x_o − x_i ∥ n_i, above or below, incl. exactly at the virtual sources
  kGrazing,             // w_i·n_i ∈ {0, ±1e-12, 1e-7, 1e-4} and μ0 → 0 (n_o ⊥ ω12)
  kBacklit,             // w_i·n_i < 0, or n_o along the refracted ray (μ0 ≤ 0)
  kAbsorptionDominated, // σ_a ≫ σ_s, incl. σ_s = 0
  kNoAbsorption,        // σ_a → 0, incl. exactly 0
  kAnisotropic,         // g = ±0.99, ±0.999
  kIndexMatched,        // η = 1
  kIndexBelowOne,       // η < 1, incl. total internal reflection
  kFarAway,             // x_i, x_o up to 1e4 mm from the origin, |x_o − x_i| from 1e-6 to 1e4
  kKindCount
};

class Generator {
 public:
  explicit Generator(std::uint64_t seed) : rng_(seed) {}

  double uniform() { return u_(rng_); }
  double logUniform(double lo, double hi) { return lo * std::pow(hi / lo, uniform()); }
  dvec3 unit() {
    dvec3 v(n_(rng_), n_(rng_), n_(rng_));
    const double l = glm::length(v);
    return l > 0 ? v / l : dvec3(0, 0, 1);
  }
  /// A unit vector ⊥ n.
  dvec3 tangent(const dvec3& n) {
    dvec3 t = glm::cross(n, unit());
    const double l = glm::length(t);
    return l > 1e-6 ? t / l : glm::normalize(glm::cross(n, std::abs(n.x) < 0.9 ? dvec3(1, 0, 0) : dvec3(0, 1, 0)));
  }
  double length() { return logUniform(1e-6, 1e4); }
  double coefficient() { return logUniform(1e-4, 1e3); }

  BssrdfConfig make(int kind) {
    BssrdfConfig c;
    c.xi = dvec3(uniform() - 0.5, uniform() - 0.5, uniform() - 0.5) * 10.0;
    c.ni = unit();
    c.wi = unit();
    if (glm::dot(c.wi, c.ni) < 0) c.wi = -c.wi;
    c.no = unit();
    c.xo = c.xi + length() * unit();
    c.sigma_a = coefficient();
    c.sigma_s = coefficient();
    c.g = 0.99 * (2 * uniform() - 1);
    c.eta = 0.5 + 2 * uniform();
    switch (kind) {
      case kRandom: break;
      case kPlanar:
        c.no = c.ni;
        c.xo = c.xi + length() * tangent(c.ni);
        break;
      case kCoincident:
        c.xo = c.xi;
        if (uniform() < 0.5) c.no = c.ni;
        break;
      case kAlongNormal: {
        const BssrdfCoefficients k = bssrdfCoefficients(c.sigma_a, c.sigma_s, c.g, c.eta);
        const double choices[4] = {length(), -length(), 2 * k.A * k.d_e, 2 * k.z_b};
        c.xo = c.xi + choices[static_cast<int>(uniform() * 4) & 3] * c.ni;
        if (uniform() < 0.5) c.no = c.ni;
        break;
      }
      case kGrazing: {
        const double cosines[5] = {0.0, 1e-12, -1e-12, 1e-7, 1e-4};
        const double ci = cosines[static_cast<int>(uniform() * 5) % 5];
        c.wi = glm::normalize(ci * c.ni + std::sqrt(1 - ci * ci) * tangent(c.ni));
        if (uniform() < 0.5) {
          const dvec3 w12 = bssrdf_stability_shared::refractedDirection(c.wi, c.ni, c.eta);
          c.no = tangent(w12);  // μ0 = 0 up to rounding
          if (uniform() < 0.5) c.xo = c.xi + length() * tangent(c.ni);
        }
        if (uniform() < 0.3) c.xo = c.xi;
        break;
      }
      case kBacklit:
        if (uniform() < 0.5) {
          c.wi = -c.wi;
        } else {
          const dvec3 w12 = bssrdf_stability_shared::refractedDirection(c.wi, c.ni, c.eta);
          c.no = glm::normalize(w12 + 0.3 * uniform() * unit());
          c.xo = c.xi + length() * (uniform() < 0.5 ? w12 : -c.ni);
        }
        break;
      case kAbsorptionDominated:
        c.sigma_a = logUniform(1, 1e3);
        c.sigma_s = uniform() < 0.2 ? 0.0 : c.sigma_a * logUniform(1e-9, 1e-3);
        break;
      case kNoAbsorption: {
        const double choices[3] = {0.0, 1e-12, 1e-8};
        c.sigma_a = choices[static_cast<int>(uniform() * 3) % 3];
        c.sigma_s = logUniform(1e-3, 1e3);
        break;
      }
      case kAnisotropic: {
        const double choices[4] = {0.99, -0.99, 0.999, -0.999};
        c.g = choices[static_cast<int>(uniform() * 4) & 3];
        break;
      }
      case kIndexMatched: c.eta = 1.0; break;
      case kIndexBelowOne:
        c.eta = 0.5 + 0.5 * uniform();
        if (uniform() < 0.5) {  // beyond the critical angle
          const double sinI = c.eta + (1 - c.eta) * uniform();
          c.wi = glm::normalize(std::sqrt(1 - sinI * sinI) * c.ni + sinI * tangent(c.ni));
        }
        break;
      case kFarAway: {
        const dvec3 origin = logUniform(1, 1e4) * unit();
        c.xi += origin;
        c.xo = c.xi + length() * unit();
        break;
      }
      default: break;
    }
    return c;
  }

 private:
  std::mt19937_64 rng_;
  std::uniform_real_distribution<double> u_{0.0, 1.0};
  std::normal_distribution<double> n_;
};

/// frontlit/backlit × near/far, index = 2·backlit + far.
int regionOf(const BssrdfConfig& c) {
  const dvec3 w12 = bssrdf_stability_shared::refractedDirection(c.wi, c.ni, c.eta);
  const bool backlit = -glm::dot(c.no, w12) <= 1e-6;  // the directional dipole's test (Eq. 24)
  const double sigmaTp = c.sigma_a + c.sigma_s * (1 - c.g);
  const bool far = glm::length(c.xo - c.xi) * sigmaTp >= 1;
  return 2 * int(backlit) + int(far);
}
constexpr const char* kRegionNames[4] = {"frontlit near", "frontlit far", "backlit near", "backlit far"};

struct Tally {
  long count[4] = {}, negative[4] = {}, nonFinite = 0;
};

TEST(BssrdfStability, TenMillionHardConfigurationsAreFiniteInFloatAndDouble) {
  const auto start = std::chrono::steady_clock::now();
  long evaluations = 0;
  for (std::size_t m = 0; m < kModels.size(); ++m) {
    const BssrdfModel model = kModels[m];
    Tally tally[2], planar[2];  // float, double; planar: the kPlanar configurations alone
    Generator gen(1000 + m);
    for (long i = 0; i < kConfigsPerModel[m]; ++i) {
      const BssrdfConfig c = gen.make(static_cast<int>(i % kKindCount));
      validateBssrdfConfig(c);  // every configuration drawn is a valid one
      const bool reciprocal = i % 16 == 15;
      const int region = regionOf(c);
      const BssrdfValue v[2] = {evaluateBssrdf<float>(model, c, reciprocal),
                                evaluateBssrdf<double>(model, c, reciprocal)};
      evaluations += 2;
      for (int p = 0; p < 2; ++p) {
        Tally& t = tally[p];
        if (!std::isfinite(v[p].sd) || !std::isfinite(v[p].sdClamped)) {
          if (t.nonFinite++ < 5)
            ADD_FAILURE() << bssrdfModelName(model) << (p ? " double" : " float") << " kind " << i % kKindCount
                          << ": sd = " << v[p].sd << " for xi " << c.xi.x << "," << c.xi.y << "," << c.xi.z << " ni "
                          << c.ni.x << "," << c.ni.y << "," << c.ni.z << " wi " << c.wi.x << "," << c.wi.y << ","
                          << c.wi.z << " xo " << c.xo.x << "," << c.xo.y << "," << c.xo.z << " no " << c.no.x << ","
                          << c.no.y << "," << c.no.z << " sa " << c.sigma_a << " ss " << c.sigma_s << " g " << c.g
                          << " eta " << c.eta;
          continue;
        }
        EXPECT_GE(v[p].sdClamped, 0.0);
        ++t.count[region];
        if (v[p].sd < 0) ++t.negative[region];
        if (i % kKindCount == kPlanar) {
          ++planar[p].count[region];
          if (v[p].sd < 0) ++planar[p].negative[region];
        }
      }
    }
    for (int p = 0; p < 2; ++p) {
      EXPECT_EQ(tally[p].nonFinite, 0) << bssrdfModelName(model) << (p ? " double" : " float");
      std::printf("[ stable  ] %-11s %-6s: %ld configurations, non-finite %ld; negative raw S_d:",
                  std::string(bssrdfModelName(model)).c_str(), p ? "double" : "float", kConfigsPerModel[m],
                  tally[p].nonFinite);
      for (int r = 0; r < 4; ++r)
        std::printf(" %s %.2f%% (of %ld)%s", kRegionNames[r],
                    tally[p].count[r] ? 100.0 * tally[p].negative[r] / tally[p].count[r] : 0.0, tally[p].count[r],
                    r < 3 ? "," : "\n");
      std::printf("[ stable  ] %-11s %-6s: of which planar (x_o on the tangent plane, n_o = n_i):",
                  std::string(bssrdfModelName(model)).c_str(), p ? "double" : "float");
      for (int r = 0; r < 4; ++r)
        std::printf(" %s %.2f%% (of %ld)%s", kRegionNames[r],
                    planar[p].count[r] ? 100.0 * planar[p].negative[r] / planar[p].count[r] : 0.0,
                    planar[p].count[r], r < 3 ? "," : "\n");
    }
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("[ stable  ] %ld evaluations in %.1f s\n", evaluations, seconds);
  EXPECT_GE(evaluations, 10'000'000);
}

}  // namespace
}  // namespace tallow::sss
