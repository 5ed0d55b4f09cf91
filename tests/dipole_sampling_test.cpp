// The image-space method's sampler without GL (docs/image-space.md, "Tests"): the exact importance
// sampling of the standard dipole's R_d (shaders/maps/dipole_sampling.glsl) and the combined pattern
// and tangent-plane Jacobian (shaders/peers/image_space/sampling.glsl), compiled here from the same files
// the GPU runs, in double and in float. Expected values come from this file: R_d and its CDF by
// numerical integration of the test's own R_d (tests/support/dipole_totals.h), the term's CDF in
// closed form in long double, the Jacobian by finite differences on a sphere.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "gpu/glsl_shared.h"
#include "support/dipole_totals.h"

namespace tallow::dipole_sampling_f64 {
using namespace glm;
using uint = std::uint32_t;
using real = double;
using real2 = glm::dvec2;
using real3 = glm::dvec3;
#include "sss/bssrdf/bssrdf_models.inc"
#include "shaders/maps/estimator.glsl"
#include "shaders/maps/dipole_sampling.glsl"
#include "shaders/peers/image_space/sampling.glsl"
}  // namespace tallow::dipole_sampling_f64

namespace tallow::dipole_sampling_f32 {
using namespace glm;
using uint = std::uint32_t;
using real = float;
using real2 = glm::vec2;
using real3 = glm::vec3;
#include "sss/bssrdf/bssrdf_models.inc"
#include "shaders/maps/estimator.glsl"
#include "shaders/maps/dipole_sampling.glsl"
#include "shaders/peers/image_space/sampling.glsl"
}  // namespace tallow::dipole_sampling_f32

namespace tallow {
namespace {

namespace d64 = dipole_sampling_f64;
namespace d32 = dipole_sampling_f32;
constexpr double kPi = 3.14159265358979323846;

/// One colour band's optical properties [mm⁻¹].
struct Band {
  const char* name;
  double sigmaA, sigmaS, g, eta;
};

// Measured bands (Jensen et al. 2001, ../shared/data/materials.csv, g = 0), a low-albedo medium, one
// without absorption, and the marble band scaled by 10⁻⁴ and 10⁴ (tiny and huge σ).
const Band kBands[] = {
    {"marble red", 0.0021, 2.19, 0.0, 1.5},      {"marble blue", 0.0071, 3.0, 0.0, 1.5},
    {"skim milk red", 0.0014, 0.70, 0.0, 1.3},   {"ketchup red", 0.061, 0.18, 0.0, 1.3},
    {"low albedo", 1.0, 0.05, 0.0, 1.3},         {"no absorption", 0.0, 1.0, 0.0, 1.3},
    {"forward scattering", 0.01, 2.0, 0.9, 1.4}, {"tiny sigma", 0.0021e-4, 2.19e-4, 0.0, 1.5},
    {"huge sigma", 0.0021e4, 2.19e4, 0.0, 1.5},
};

d64::BssrdfCoefficients coefficients(const Band& b) { return d64::bssrdfCoefficients(b.sigmaA, b.sigmaS, b.g, b.eta); }

/// The test's own R_d [mm⁻²] (Jensen et al. 2001, Eq. 5; tests/support/dipole_totals.h).
double rd(const Band& b, double r) { return test::jensenRd(r, b.sigmaA, b.sigmaS, b.g, b.eta); }

/// Adaptive Simpson on [a, b] to `tol` absolute.
double simpson(const std::function<double(double)>& f, double a, double b, double fa, double fm, double fb,
               double whole, double tol, int depth) {
  const double m = 0.5 * (a + b), fl = f(0.5 * (a + m)), fr = f(0.5 * (m + b));
  const double left = (m - a) / 6.0 * (fa + 4.0 * fl + fm), right = (b - m) / 6.0 * (fm + 4.0 * fr + fb);
  const double delta = left + right - whole;
  if (depth >= 20 || std::abs(delta) <= 15.0 * std::max(tol, 1e-15 * std::abs(left + right)))
    return left + right + delta / 15.0;
  return simpson(f, a, m, fa, fl, fm, left, 0.5 * tol, depth + 1) + simpson(f, m, b, fm, fr, fb, right, 0.5 * tol, depth + 1);
}
/// ∫_a^b f to `relTol` of the panel's first estimate (16 sub-panels first, so that no feature is missed).
double integrate(const std::function<double(double)>& f, double a, double b, double relTol) {
  if (!(b > a)) return 0.0;
  constexpr int kPanels = 16;
  double coarse = 0.0;
  std::vector<double> x(2 * kPanels + 1), y(2 * kPanels + 1);
  for (int i = 0; i <= 2 * kPanels; ++i) {
    x[i] = a + (b - a) * i / (2 * kPanels);
    y[i] = f(x[i]);
  }
  for (int i = 0; i < kPanels; ++i) coarse += (x[2 * i + 2] - x[2 * i]) / 6.0 * (y[2 * i] + 4.0 * y[2 * i + 1] + y[2 * i + 2]);
  const double tol = relTol * std::abs(coarse) / kPanels;
  double total = 0.0;
  for (int i = 0; i < kPanels; ++i) {
    const double whole = (x[2 * i + 2] - x[2 * i]) / 6.0 * (y[2 * i] + 4.0 * y[2 * i + 1] + y[2 * i + 2]);
    total += simpson(f, x[2 * i], x[2 * i + 2], y[2 * i], y[2 * i + 1], y[2 * i + 2], whole, tol, 0);
  }
  return total;
}
/// ∫₀^R f(r) dr on panels that grow geometrically from z/100 (R_d changes on the scale of z near 0
/// and of 1/σ_tr far out), each to `relTol` of itself (a float integrand is noisy at 10⁻⁷).
double integrateRadially(const std::function<double(double)>& f, double z, double R, double relTol = 1e-12) {
  double total = 0.0, a = 0.0, b = std::min(0.01 * z, R);
  while (a < R) {
    total += integrate(f, a, b, relTol);
    a = b;
    b = std::min(R, b * 1.5);
  }
  return total;
}

// --- The helpers -------------------------------------------------------------------------------

TEST(DipoleSampling, Log1pAndExpm1KeepTheirDigitsInFloat) {
  // The series branch and the direct branch meet at |x| = 0.05; in float the direct branch is good
  // to 2⁻²⁴/0.05 ≈ 1.2·10⁻⁶ relative, the series to rounding (≈ 10⁻⁷).
  for (double x : {-0.9, -0.5, -0.1, -0.0500001, -0.05, -0.0499999, -0.01, -1e-3, -1e-5, -1e-8, -1e-20, 1e-20, 1e-8,
                   1e-5, 1e-3, 0.01, 0.0499999, 0.05, 0.0500001, 0.1, 0.5, 1.0, 3.0}) {
    const auto xf = static_cast<float>(x);
    EXPECT_NEAR(d32::dipoleLog1p(xf) / std::log1p(double(xf)), 1.0, 2e-6) << x;
    EXPECT_NEAR(d32::dipoleExpm1(xf) / std::expm1(double(xf)), 1.0, 2e-6) << x;
    EXPECT_NEAR(d64::dipoleLog1p(x) / std::log1p(x), 1.0, 1e-14) << x;
    EXPECT_NEAR(d64::dipoleExpm1(x) / std::expm1(x), 1.0, 1e-14) << x;
  }
}

// --- The density ---------------------------------------------------------------------------------

TEST(DipoleSampling, DensityIntegratesToOneOnTheDisc) {
  // ∫₀^R p(r) 2πr dr by the test's quadrature of the sampler's own pdf (R_d/total, the shared
  // lines), for discs of 1, 8 and 10⁴ mean free paths: 1 to 10⁻⁸ (the quadrature's tolerance
  // is 10⁻¹³ per panel; the closed-form total and the shared R_d agree to rounding). The float
  // instantiation to 10⁻⁵ (float rounding of R_d and of total, ~10⁻⁷ each, summed over panels).
  for (const Band& b : kBands)
    for (double mfps : {1.0, 8.0, 1e4}) {
      const auto k = coefficients(b);
      const double R = mfps * d64::dipoleMeanFreePath(k);
      const d64::DipoleSampler s = d64::dipoleSampler(k, R);
      const double mass = integrateRadially([&](double r) { return d64::dipoleAreaPdf(s, r) * 2.0 * kPi * r; }, k.zr, R);
      EXPECT_NEAR(mass, 1.0, 1e-8) << b.name << ", " << mfps << " mfp";
      // The density is the test's R_d over its integral on the disc (the sampler's total is that integral).
      const double testMass = integrateRadially([&](double r) { return rd(b, r) * 2.0 * kPi * r; }, k.zr, R);
      EXPECT_NEAR(s.total / testMass, 1.0, 1e-8) << b.name << ", " << mfps << " mfp";
      const auto kf = d32::bssrdfCoefficients(float(b.sigmaA), float(b.sigmaS), float(b.g), float(b.eta));
      const d32::DipoleSampler sf = d32::dipoleSampler(kf, float(R));
      const double massF = integrateRadially(
          [&](double r) { return double(d32::dipoleAreaPdf(sf, float(r))) * 2.0 * kPi * r; }, k.zr, R, 1e-7);
      EXPECT_NEAR(massF, 1.0, 1e-5) << b.name << ", " << mfps << " mfp (float)";
    }
  // Against the published total: on a disc of 10⁴ mean free paths the sampler's total is Jensen et
  // al.'s R_d = (α'/2)(1 + e^{−(4/3)A√(3(1−α'))}) e^{−√(3(1−α'))} (the tail beyond is < 10⁻⁸).
  for (const Band& b : kBands) {
    if (b.sigmaA == 0.0) continue;  // σ_a = 0: R_d falls off as z/r³, the tail z/R is 10⁻⁴ of it here
    const auto k = coefficients(b);
    const double total = d64::dipoleSampler(k, 1e4 * d64::dipoleMeanFreePath(k)).total;
    EXPECT_NEAR(total / test::jensenTotalRd(b.sigmaA, b.sigmaS, b.g, b.eta), 1.0, 1e-8) << b.name;
  }
}

TEST(DipoleSampling, NoneOfTheHardCasesGivesNaN) {
  // α' = 0 (no scattering: R_d ≡ 0), σ_a = 0, extreme scales, r at and beyond the disc's edge.
  const Band hard[] = {{"no scattering", 1.0, 0.0, 0.0, 1.3}, {"no absorption", 0.0, 1.0, 0.0, 1.3},
                       {"tiny", 1e-9, 1e-7, 0.0, 1.3},       {"huge", 1e5, 1e6, 0.0, 1.3},
                       {"eta 2.5", 0.01, 1.0, 0.0, 2.5},     {"eta 1", 0.01, 1.0, 0.0, 1.0}};
  for (const Band& b : hard)
    for (double mfps : {0.5, 8.0, 64.0}) {
      const auto kf = d32::bssrdfCoefficients(float(b.sigmaA), float(b.sigmaS), float(b.g), float(b.eta));
      const auto e = d32::isPatternEntry(kf, kf, kf, float(mfps), 5, 16, 4, 3u, 7u);
      EXPECT_TRUE(std::isfinite(e.weight) && std::isfinite(e.offset.x) && std::isfinite(e.coverage.x)) << b.name;
      for (float xi : {0.0f, 1e-7f, 0.5f, 0.99999994f, 1.0f}) {
        const d32::DipoleSampler s = d32::dipoleSampler(kf, float(mfps) * d32::dipoleMeanFreePath(kf));
        const float r = d32::dipoleSampleRadius(s, xi).r;
        EXPECT_TRUE(std::isfinite(r) && r >= 0.0f && r <= s.radius * 1.000001f) << b.name << " xi " << xi;
        EXPECT_TRUE(std::isfinite(d32::dipoleAreaPdf(s, r))) << b.name;
      }
    }
}

// --- The samples follow R_d(r) r: Kolmogorov–Smirnov ----------------------------------------------

/// The KS statistic of sorted samples against the CDF of R_d(r) 2πr on [0, R], that CDF integrated
/// here from the test's R_d between consecutive samples.
double ksStatistic(const Band& b, std::vector<double> r, double R) {
  std::sort(r.begin(), r.end());
  const auto k = coefficients(b);
  const auto density = [&](double x) { return rd(b, x) * 2.0 * kPi * x; };
  const double total = integrateRadially(density, k.zr, R);
  double cdf = 0.0, previous = 0.0, d = 0.0;
  const double n = static_cast<double>(r.size());
  for (std::size_t i = 0; i < r.size(); ++i) {
    // Between samples the CDF grows by ∫ over [previous, r_i]; geometric panels for long gaps.
    double a = previous;
    while (a < r[i]) {
      const double bEnd = std::min(r[i], std::max(2.0 * a, a + 0.01 * k.zr));
      cdf += integrate(density, a, bEnd, 1e-10);
      a = bEnd;
    }
    previous = r[i];
    const double g = cdf / total;
    d = std::max({d, std::abs(g - double(i) / n), std::abs(double(i + 1) / n - g)});
  }
  return d;
}

// n = 20000 independent samples; at significance α = 0.001 the one-sample KS critical value is
// √(−ln(α/2)/2)/√n = 1.9495/√n = 0.01378 (asymptotic Kolmogorov distribution; at this n the
// finite-sample correction is below 10⁻⁴). The seed is fixed, so the test is deterministic; a
// correct sampler exceeds the value with probability 0.001 per case.
constexpr int kKsSamples = 20000;
const double kKsCritical = std::sqrt(-std::log(0.001 / 2.0) / 2.0) / std::sqrt(double(kKsSamples));

TEST(DipoleSampling, SamplesFollowRdTimesRByKolmogorovSmirnov) {
  std::mt19937_64 rng(20030611);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  for (const Band& b : kBands)
    for (double mfps : {2.0, 8.0}) {
      const auto k = coefficients(b);
      const double R = mfps * d64::dipoleMeanFreePath(k);
      const d64::DipoleSampler s = d64::dipoleSampler(k, R);
      const auto kf = d32::bssrdfCoefficients(float(b.sigmaA), float(b.sigmaS), float(b.g), float(b.eta));
      const d32::DipoleSampler sf = d32::dipoleSampler(kf, float(R));
      std::vector<double> r64, r32;
      for (int i = 0; i < kKsSamples; ++i) {
        const double xi = uniform(rng);
        r64.push_back(d64::dipoleSampleRadius(s, xi).r);
        r32.push_back(double(d32::dipoleSampleRadius(sf, float(xi)).r));
      }
      const double d64stat = ksStatistic(b, r64, R), d32stat = ksStatistic(b, r32, R);
      std::printf("[ sampling ] %-18s %4.0f mfp: KS D = %.5f (double), %.5f (float), critical %.5f\n", b.name, mfps,
                  d64stat, d32stat, kKsCritical);
      EXPECT_LT(d64stat, kKsCritical) << b.name << ", " << mfps << " mfp";
      EXPECT_LT(d32stat, kKsCritical) << b.name << ", " << mfps << " mfp (float)";
    }
}

TEST(DipoleSampling, KolmogorovSmirnovRejectsTheExponentialSamplerOfTheRadiosityMaps) {
  // The test has power: distances drawn from σ_tr e^{−σ_tr r} (the radiosity maps' Eq. 12, a good
  // sampler of the far field but not of R_d r) are rejected, as is the real source alone.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const Band& b = kBands[0];
  const auto k = coefficients(b);
  const double R = 8.0 * d64::dipoleMeanFreePath(k);
  std::vector<double> exponential, realOnly;
  const double cut = 1.0 - std::exp(-k.sigmaTr * R);  // the exponential truncated to the same disc
  for (int i = 0; i < kKsSamples; ++i) {
    exponential.push_back(-std::log1p(-uniform(rng) * cut) / k.sigmaTr);
    realOnly.push_back(d64::dipoleInvertTerm(k.zr, k.sigmaTr, uniform(rng) * d64::dipoleTermShare(k.zr, k.sigmaTr, R)).r);
  }
  const double dExp = ksStatistic(b, exponential, R), dReal = ksStatistic(b, realOnly, R);
  std::printf("[ sampling ] KS D of the exponential sampler %.4f, of the real source alone %.4f\n", dExp, dReal);
  EXPECT_GT(dExp, 5.0 * kKsCritical);
  EXPECT_GT(dReal, kKsCritical);
}

// --- Newton's inversion ------------------------------------------------------------------------------

/// c(r) = −log(1 − F(r)) = σ_tr (d − z) + log(d/z) of one term, in long double: the quantity the
/// inversion equates to c = −log(1 − share).
long double termC(long double z, long double sigmaTr, long double r) {
  const long double d = std::sqrt(r * r + z * z), dz = r * r / (d + z);
  return sigmaTr * dz + std::log1p(dz / z);
}

TEST(DipoleSampling, NewtonConvergesAtTheHardEnds) {
  // a = σ_tr z from 0 (no absorption) to 40 (the virtual source at η = 2.5 in a dark medium) and
  // beyond, z from 10⁻⁶ to 10⁶ mm, shares from 0 (r → 0) to 1 − 2⁻²⁴ (the largest r): the
  // residual |c(r) − c| of the equation a w + log1p(w) = c, in units of 1 + c, is at rounding
  // level — 10⁻¹³ in double, 2·10⁻⁶ in units of 1 + a + c in float (r carries a few float roundings
  // and r dc/dr ≤ 2(1 + a + c)) — within 8 steps in
  // double and float alike (the cap, 40, is never reached).
  const double as[] = {0.0, 1e-12, 1e-6, 1e-3, 0.1, 1.0, std::sqrt(3.0), 10.0, 40.0, 1e3};
  const double zs[] = {1e-6, 1e-2, 1.0, 1e6};
  const double shares[] = {0.0, 1e-30, 1e-12, 1e-6, 1e-3, 0.1, 0.5, 0.9, 0.999, 1.0 - 1e-6, 0.99999994039535522};
  int worst = 0, worstF = 0;
  for (double a : as)
    for (double z : zs)
      for (double share : shares) {
        const double sigma = a / z;
        const d64::DipoleInversion inv = d64::dipoleInvertTerm(z, sigma, share);
        const long double c = -std::log1p(-static_cast<long double>(share));
        ASSERT_TRUE(std::isfinite(inv.r) && inv.r >= 0.0) << a << ' ' << z << ' ' << share;
        const long double residual = std::abs(termC(z, sigma, inv.r) - c) / (1.0L + c);
        EXPECT_LT(static_cast<double>(residual), 1e-13) << "a " << a << " z " << z << " share " << share;
        if (share == 0.0) {
          EXPECT_EQ(inv.r, 0.0);
        }
        worst = std::max(worst, inv.iterations);
        const d32::DipoleInversion f = d32::dipoleInvertTerm(float(z), float(sigma), float(share));
        ASSERT_TRUE(std::isfinite(f.r) && f.r >= 0.0f) << a << ' ' << z << ' ' << share;
        const long double cf = -std::log1p(-static_cast<long double>(float(share)));
        const long double residualF =
            std::abs(termC(float(z), float(sigma), f.r) - cf) / (1.0L + a + cf);
        EXPECT_LT(static_cast<double>(residualF), 2e-6) << "float: a " << a << " z " << z << " share " << share;
        worstF = std::max(worstF, f.iterations);
      }
  std::printf("[ sampling ] Newton: at most %d steps (double), %d (float)\n", worst, worstF);
  EXPECT_LE(worst, 8);
  EXPECT_LE(worstF, 8);
}

// --- The combined pattern (balance heuristic) -------------------------------------------------------

TEST(DipoleSampling, CombinedPatternEstimatesIntegralsOverTheDiscWithoutBias) {
  // For f(r, φ) = R_d,b(r) (1 + cos φ)·[r < R/2] + 1/R² (a profile, an angular variation, a cut
  // that importance sampling does not see, a constant only the uniform samples cover well), Σ_j
  // f(x_j) weight_j averaged over 4000 sets and frames must equal ∫_disc f dA = ∫₀^{R/2} R_d 2πr dr
  // + π: within 4 standard errors of that mean (the sets are independent through their rotations).
  const Band& b0 = kBands[0];
  const Band& b1 = kBands[1];
  const Band& b2 = kBands[4];
  const auto k0 = coefficients(b0), k1 = coefficients(b1), k2 = coefficients(b2);
  const double mfps = 8.0, R = d64::isDiscRadius(k0, k1, k2, mfps);
  const int n = 12;
  for (int nUniform : {0, 3, 12}) {
    for (int band = 0; band < 3; ++band) {
      const Band& bb = band == 0 ? b0 : band == 1 ? b1 : b2;
      // Without uniform samples the constant's weight is unbounded at the disc's edge (the heavy tail
      // that combined sampling removes, §6.1): it is left out there.
      const double constant = nUniform > 0 ? 1.0 / (R * R) : 0.0;
      const double expected =
          integrateRadially([&](double r) { return rd(bb, r) * 2.0 * kPi * r; }, coefficients(bb).zr, 0.5 * R) +
          constant * kPi * R * R;
      double sum = 0.0, sum2 = 0.0, coverage = 0.0;
      const int sets = 4000;
      for (int s = 0; s < sets; ++s) {
        double estimate = 0.0;
        for (int j = 0; j < n; ++j) {
          const d64::IsPatternEntry e =
              d64::isPatternEntry(k0, k1, k2, mfps, j, n, nUniform, static_cast<std::uint32_t>(s % 16),
                                  static_cast<std::uint32_t>(s / 16));
          const double r = glm::length(e.offset), cosPhi = r > 0.0 ? e.offset.x / r : 1.0;
          const double f = (r < 0.5 * R ? rd(bb, r) * (1.0 + cosPhi) : 0.0) + constant;
          estimate += f * e.weight;
          coverage += e.coverage[band];
        }
        sum += estimate;
        sum2 += estimate * estimate;
      }
      const double mean = sum / sets, stderror = std::sqrt(std::max(sum2 / sets - mean * mean, 0.0) / sets);
      std::printf("[ sampling ] pattern, %2d uniform of %d, band %d: %.6f against %.6f (%.2f standard errors), "
                  "coverage %.4f\n",
                  nUniform, n, band, mean, expected, (mean - expected) / stderror, coverage / sets);
      EXPECT_LT(std::abs(mean - expected), 4.0 * stderror + 1e-12 * expected) << nUniform << " band " << band;
      // Σ_j p_b weight_j is the same estimator for f = p_b, whose integral is 1 (every sample valid);
      // with importance samples among them its spread is a few per cent per set (uniform samples
      // alone see the peak of p_b too rarely for 4000 sets to average it).
      if (nUniform < n) {
        EXPECT_NEAR(coverage / sets, 1.0, 0.01) << nUniform << " band " << band;
      }
    }
  }
}

TEST(DipoleSampling, StrategyCountsPartitionTheSet) {
  for (int n = 1; n <= 40; ++n)
    for (int u = 0; u <= n; ++u) {
      int counts[4] = {0, 0, 0, 0};
      for (int j = 0; j < n; ++j) {
        const int s = d64::isStrategy(j, u);
        EXPECT_EQ(d64::isStrategyIndex(j, u), counts[s + 1]) << n << ' ' << u << ' ' << j;
        counts[s + 1]++;
      }
      for (int s = -1; s < 3; ++s) EXPECT_EQ(d64::isStrategyCount(s, n, u), counts[s + 1]) << n << ' ' << u << ' ' << s;
    }
}

// --- The tangent plane's Jacobian ----------------------------------------------------------------------

/// First hit of the ray o + t d (d unit) on the sphere (centre c, radius ρ), or NaN.
glm::dvec3 hitSphere(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& c, double rho) {
  const glm::dvec3 oc = o - c;
  const double b = glm::dot(oc, d), q = glm::dot(oc, oc) - rho * rho, disc = b * b - q;
  if (disc < 0.0) return glm::dvec3(NAN);
  const double t = -b - std::sqrt(disc);
  return o + t * d;
}

TEST(DipoleSampling, AreaRatioMatchesTheProjectionOntoASphere) {
  // A small square of side h around p' in the tangent plane of x_o, each corner projected along its
  // camera ray onto the sphere: the projected quad's area over h² must equal isAreaRatio at p'
  // (to O(h/ρ) = 10⁻⁵ plus the curvature of the quad, tolerance 10⁻⁴ relative), for perspective and
  // orthographic cameras, near and grazing views.
  const glm::dvec3 c(0.0, 0.0, 0.0);
  const double rho = 1.0, h = 1e-5;
  for (int ortho = 0; ortho < 2; ++ortho)
    for (double view : {0.0, 0.5, 1.0}) {
      const glm::dvec3 eye(0.0, 0.3, 4.0), forward = glm::normalize(c - eye);
      const glm::dvec3 no = glm::normalize(glm::dvec3(std::sin(view), 0.2, std::cos(view)));
      const glm::dvec3 xo = c + rho * no;
      const glm::dvec3 t1 = glm::normalize(glm::cross(no, glm::dvec3(0, 1, 0))), t2 = glm::cross(no, t1);
      for (double offset : {0.05, 0.2, 0.4}) {
        const glm::dvec3 pp = xo + offset * (0.6 * t1 + 0.8 * t2);
        const auto project = [&](const glm::dvec3& q) {
          const glm::dvec3 d = ortho ? forward : glm::normalize(q - eye);
          return hitSphere(ortho ? q - 10.0 * forward : eye, d, c, rho);
        };
        const glm::dvec3 a = project(pp - 0.5 * h * t1 - 0.5 * h * t2), b = project(pp + 0.5 * h * t1 - 0.5 * h * t2),
                         cc = project(pp + 0.5 * h * t1 + 0.5 * h * t2), d = project(pp - 0.5 * h * t1 + 0.5 * h * t2);
        const glm::dvec3 p = project(pp);
        if (std::isnan(p.x) || std::isnan(a.x) || std::isnan(cc.x)) continue;
        const double area = 0.5 * glm::length(glm::cross(cc - a, d - b));
        const glm::dvec3 np = glm::normalize(p - c);
        if (std::abs(glm::dot(ortho ? forward : glm::normalize(p - eye), np)) < 0.1) continue;  // near the limb
        const double ratio = d64::isAreaRatio(pp, no, p, np, eye, forward, ortho);
        EXPECT_NEAR(area / (h * h) / ratio, 1.0, 1e-4) << "ortho " << ortho << " view " << view << " offset " << offset;
      }
    }
}

}  // namespace
}  // namespace tallow
