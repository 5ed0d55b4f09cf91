// Christensen and Burley's normalised diffusion profile (`method=burley`, shaders/peers/burley/
// profile.glsl compiled in double): its integral over the plane is the albedo it is given, its
// radius sampling has the density it claims, its transmittance is the profile's mass beyond the
// thickness, and its albedo is the standard dipole's total — each against an independent
// computation (numerical quadrature, a histogram, tests/support/dipole_totals.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "sss/peers/burley_profile.h"
#include "support/dipole_totals.h"

namespace tallow::sss {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// Media from a thin, bright one to a dark, absorbing one (σ in mm⁻¹), η 1.3 to 1.5.
std::vector<Material> media() {
  std::vector<Material> out;
  const auto add = [&](glm::vec3 sa, glm::vec3 ss, float g, float eta) {
    Material m;
    m.sigma_a = sa;
    m.sigma_s = ss;
    m.g = glm::vec3(g);
    m.eta = eta;
    out.push_back(m);
  };
  add({0.0021f, 0.0041f, 0.0071f}, {2.19f, 2.62f, 3.00f}, 0.0f, 1.5f);  // marble-like
  add({0.0011f, 0.0024f, 0.014f}, {2.55f, 3.21f, 3.77f}, 0.0f, 1.3f);  // skim-milk-like
  add({0.5f, 1.0f, 2.0f}, {1.0f, 0.8f, 0.5f}, 0.5f, 1.4f);              // dark, forward scattering
  return out;
}

/// ∫_a^b f(r) dr by Simpson's rule on a logarithmic grid (the profile spans decades).
template <typename F>
double integrateLog(F f, double a, double b, int steps = 20000) {
  const double la = std::log(a), lb = std::log(b), h = (lb - la) / steps;
  double sum = 0.0;
  for (int i = 0; i <= steps; ++i) {
    const double x = la + i * h, r = std::exp(x);
    const double w = (i == 0 || i == steps) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    sum += w * f(r) * r;  // dr = r dx
  }
  return sum * h / 3.0;
}

TEST(BurleyProfile, IntegratesToItsAlbedoOverThePlane) {
  for (const Material& m : media())
    for (const BurleyBandParams& b : burleyBands(m)) {
      const double total =
          integrateLog([&](double r) { return 2.0 * kPi * r * burleyProfile(r, b); }, 1e-9 * b.d, 200.0 * b.d);
      EXPECT_NEAR(total, b.albedo, 1e-6 * b.albedo) << "d " << b.d;
    }
}

TEST(BurleyProfile, AlbedoIsTheStandardDipolesTotalAndDTheMeanFreePathOverTheFit) {
  for (const Material& m : media()) {
    const auto bands = burleyBands(m);
    for (int c = 0; c < 3; ++c) {
      const double a = test::jensenTotalRd(m.sigma_a[c], m.sigma_s[c], m.g[c], m.eta);
      EXPECT_NEAR(bands[c].albedo, a, 1e-12) << "band " << c;
      // ℓ / d is the memo's fit 1.85 − A + 7|A − 0.8|³ (searchlight, mean free path).
      const double ell = 1.0 / (m.sigma_a[c] + m.sigma_s[c] * (1.0 - m.g[c]));
      EXPECT_NEAR(ell / bands[c].d, 1.85 - a + 7.0 * std::pow(std::abs(a - 0.8), 3.0), 1e-9) << "band " << c;
    }
  }
}

TEST(BurleyProfile, SampledRadiiFollowTheirDensity) {
  // 400 000 radii into 40 bins of equal probability under the claimed density (its CDF by
  // quadrature): each bin's count within 5 standard deviations of 10 000, and the chi-square of
  // the 40 bins below its 99.9% quantile (73.4 for 39 degrees of freedom).
  const double d = 1.7;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  constexpr int kBins = 40, kSamples = 400000;
  // Bin edges: CDF(r) = k / kBins, the CDF integrated numerically from the density.
  std::vector<double> edges;
  {
    double cdf = 0.0, r = 0.0;
    const double dr = d * 1e-4;
    for (int k = 1; k < kBins; ++k) {
      while (cdf < static_cast<double>(k) / kBins) {
        cdf += 0.5 * (burleyRadiusPdf(r, d) + burleyRadiusPdf(r + dr, d)) * dr;
        r += dr;
      }
      edges.push_back(r);
    }
  }
  std::vector<int> counts(kBins, 0);
  for (int i = 0; i < kSamples; ++i) {
    const double r = burleySampleRadius(u(rng), u(rng), d);
    const int bin = static_cast<int>(std::upper_bound(edges.begin(), edges.end(), r) - edges.begin());
    ++counts[static_cast<std::size_t>(bin)];
  }
  const double expected = static_cast<double>(kSamples) / kBins;
  double chi2 = 0.0;
  for (int k = 0; k < kBins; ++k) {
    EXPECT_NEAR(counts[k], expected, 5.0 * std::sqrt(expected)) << "bin " << k;
    chi2 += (counts[k] - expected) * (counts[k] - expected) / expected;
  }
  EXPECT_LT(chi2, 73.4);
}

TEST(BurleyProfile, TransmittanceIsTheProfilesMassBeyondTheThickness) {
  for (const Material& m : media())
    for (const BurleyBandParams& b : burleyBands(m)) {
      EXPECT_NEAR(burleyTransmittance(0.0, b), b.albedo, 1e-12) << "no thickness: all of it";
      for (const double t : {0.1 * b.d, b.d, 4.0 * b.d}) {
        const double beyond = integrateLog([&](double r) { return 2.0 * kPi * r * burleyProfile(r, b); }, t, 300.0 * b.d);
        EXPECT_NEAR(burleyTransmittance(t, b), beyond, 1e-6 * b.albedo) << "t " << t;
      }
    }
}

TEST(BurleyProfile, HalfPlaneMassIsTheShareOfSampledPointsBeyondTheLine) {
  // H(a), the share of the profile's mass beyond x = a, against points drawn from the profile (the
  // radius by burleySampleRadius, tested above, the angle uniform): 10^6 points, within 4 standard
  // errors; H(0) = 1/2 by symmetry.
  const double d = 0.8;
  EXPECT_NEAR(burleyHalfPlaneMass(0.0, d), 0.5, 1e-6);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  constexpr int kPoints = 1000000;
  const std::vector<double> lines = {0.05 * d, 0.5 * d, 2.0 * d, 6.0 * d};
  std::vector<int> beyond(lines.size(), 0);
  for (int i = 0; i < kPoints; ++i) {
    const double x = burleySampleRadius(u(rng), u(rng), d) * std::cos(2.0 * kPi * u(rng));
    for (std::size_t j = 0; j < lines.size(); ++j) beyond[j] += x > lines[j] ? 1 : 0;
  }
  for (std::size_t j = 0; j < lines.size(); ++j) {
    const double share = static_cast<double>(beyond[j]) / kPoints;
    const double sigma = std::sqrt(share * (1.0 - share) / kPoints);
    EXPECT_NEAR(burleyHalfPlaneMass(lines[j], d), share, 4.0 * sigma + 1e-6) << "a " << lines[j];
  }
}

TEST(BurleyProfile, SeparableTapsHoldEachBandsWholeMass) {
  // The 2K + 1 taps' weights sum to 1 per band (the centre once, the others on both sides), their
  // offsets grow from 0 to 8 d_max, and each weight is the mass of its strip (differences of H).
  for (const Material& m : media()) {
    const auto bands = burleyBands(m);
    const std::vector<BurleyTap> taps = burleySeparableTaps(bands, 8);
    ASSERT_EQ(taps.size(), 9u);
    EXPECT_EQ(taps[0].offset, 0.0);
    EXPECT_NEAR(taps.back().offset, kBurleySeparableRadius * std::max({bands[0].d, bands[1].d, bands[2].d}), 1e-12);
    for (int c = 0; c < 3; ++c) {
      double total = taps[0].weight[c];
      for (std::size_t k = 1; k < taps.size(); ++k) {
        EXPECT_GT(taps[k].offset, taps[k - 1].offset);
        EXPECT_GE(taps[k].weight[c], 0.0);
        total += 2.0 * taps[k].weight[c];
      }
      EXPECT_NEAR(total, 1.0, 1e-9) << "band " << c;
      const double m1 = 0.5 * (taps[1].offset + taps[2].offset), m0 = 0.5 * taps[1].offset;
      EXPECT_NEAR(taps[1].weight[c], burleyHalfPlaneMass(m0, bands[c].d) - burleyHalfPlaneMass(m1, bands[c].d), 1e-12);
    }
  }
}

}  // namespace
}  // namespace tallow::sss
