// The Monte Carlo estimator of scattered radiosity (sss/maps/radiosity_estimator.h, shared with the GPU
// through shaders/maps/estimator.glsl) against values derived independently here: the closed-form
// total diffuse reflectance of the standard dipole, a deterministic quadrature of the directional
// dipole over the plane, hand-computed radical inverses, stereographic projections and PCG hashes,
// and the chi-square distribution. Formulas: docs/radiosity-maps.md, "The estimator".
#include "sss/maps/radiosity_estimator.h"

#include <gtest/gtest.h>

#include "support/dipole_totals.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "sss/bssrdf/bssrdf.h"
#include "sss/bssrdf/material.h"

namespace tallow::sss {
namespace {

constexpr double kPi = 3.14159265358979323846;

RadiosityMaterial fromTable(const std::string& name) {
  const MaterialTable table = MaterialTable::load(TALLOW_TEST_DATA_DIR "/materials.csv");
  const std::optional<Material> m = table.find(name);
  EXPECT_TRUE(m.has_value()) << name;
  if (!m) return {};
  RadiosityMaterial r;
  r.sigma_a = glm::dvec3(m->sigma_a);
  r.sigma_s = glm::dvec3(m->sigma_s);
  r.g = glm::dvec3(m->g);
  r.eta = m->eta;
  return r;
}

using test::jensenTotalRd;
using test::normalTransmittance;

/// n-point Gauss–Legendre nodes and weights on [−1, 1] by Newton's method on P_n.
struct GaussLegendre {
  std::vector<double> x, w;
  explicit GaussLegendre(int n) {
    for (int i = 0; i < n; ++i) {
      double z = std::cos(kPi * (i + 0.75) / (n + 0.5)), dp = 0.0;
      for (int it = 0; it < 100; ++it) {
        double p0 = 1.0, p1 = z;
        for (int k = 2; k <= n; ++k) {
          const double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
          p0 = p1;
          p1 = p2;
        }
        dp = n * (z * p1 - p0) / (z * z - 1.0);
        const double dz = p1 / dp;
        z -= dz;
        if (std::abs(dz) < 1e-16) break;
      }
      x.push_back(z);
      w.push_back(2.0 / ((1.0 - z * z) * dp * dp));
    }
  }
};

/// ∫₀^∞ f(r) 2π r dr by 16-point Gauss–Legendre on geometrically growing panels [b_i, b_i·ratio]
/// from r = first (plus the panel [0, first]) to r = last, beyond which f is negligible.
template <class F>
double integratePlane(const F& f, double first, double last, double ratio) {
  static const GaussLegendre gl(16);
  const auto panel = [&](double a, double b) {
    double s = 0.0;
    for (size_t i = 0; i < gl.x.size(); ++i) {
      const double r = 0.5 * (a + b) + 0.5 * (b - a) * gl.x[i];
      s += gl.w[i] * f(r) * 2.0 * kPi * r;
    }
    return 0.5 * (b - a) * s;
  };
  double total = panel(0.0, first);
  for (double a = first; a < last; a *= ratio) total += panel(a, a * ratio);
  return total;
}

/// S_d (clamped, as the estimator uses it) at distance r on the plane z = 0, light at normal incidence.
double planarSd(BssrdfModel model, double r, double sa, double ss, double g, double eta) {
  BssrdfConfig c{{r, 0.0, 0.0}, {0, 0, 1}, {0, 0, 1}, {0, 0, 0}, {0, 0, 1}, sa, ss, g, eta};
  return evaluateBssrdf<double>(model, c).sdClamped;
}

ScatteredRadiosityInput slabInput(const RadiosityMaterial& m, BssrdfModel model, int samples) {
  ScatteredRadiosityInput in;
  in.xo = {0, 0, 0};
  in.no = {0, 0, 1};
  in.toLight = {0, 0, 1};
  in.irradiance = {1.0, 2.0, 0.5};
  in.material = m;
  in.model = model;
  in.samples = samples;
  return in;
}

/// The plane z = 0 seen by the light's G-buffer: every x_j hits itself with normal +z.
std::optional<LightGBufferHit> planeLookup(const glm::dvec3& xj) {
  return LightGBufferHit{{xj.x, xj.y, 0.0}, {0.0, 0.0, 1.0}};
}

struct MeanAndError {
  glm::dvec3 mean{0.0}, standardError{0.0};
};

/// The mean of `texels` independent estimates (texel x = 0 … texels − 1, frame 7) and its standard
/// error from their spread.
template <class Real>
MeanAndError slabEstimate(ScatteredRadiosityInput in, int texels) {
  glm::dvec3 sum(0.0), sum2(0.0);
  for (int t = 0; t < texels; ++t) {
    in.texelX = static_cast<std::uint32_t>(t);
    in.texelY = 3;
    in.map = 1;
    in.frame = 7;
    const ScatteredRadiosity b = estimateScatteredRadiosity<Real>(in, planeLookup);
    sum += b.B;
    sum2 += b.B * b.B;
  }
  MeanAndError out;
  out.mean = sum / double(texels);
  const glm::dvec3 var = (sum2 - sum * sum / double(texels)) / double(texels - 1);
  out.standardError = glm::sqrt(glm::max(var, glm::dvec3(0.0)) / double(texels));
  return out;
}

void report(const char* model, const char* material, int band, double mean, double se, double expected) {
  std::printf("  slab %-11s %-9s band %d: B_N %.6f ± %.6f  expected %.6f  (%+.2f%%, %+.2f σ)\n", model, material,
              band, mean, se, expected, 100.0 * (mean - expected) / expected, (mean - expected) / se);
}

// --- The analytic slab ----------------------------------------------------------------------------

class SlabStandardDipole : public ::testing::TestWithParam<const char*> {};

TEST_P(SlabStandardDipole, ConvergesToFresnelTimesIrradianceTimesTotalDiffuseReflectance) {
  const RadiosityMaterial m = fromTable(GetParam());
  const ScatteredRadiosityInput in = slabInput(m, BssrdfModel::Standard, 256);
  const MeanAndError d = slabEstimate<double>(in, 512);
  const MeanAndError f = slabEstimate<float>(in, 128);
  for (int c = 0; c < 3; ++c) {
    // Our standard dipole's own A and α' equal the closed form's (the same Jensen fit).
    const BssrdfCoefficients k = bssrdfCoefficients(m.sigma_a[c], m.sigma_s[c], m.g[c], m.eta);
    const double fdr = -1.440 / (m.eta * m.eta) + 0.710 / m.eta + 0.668 + 0.0636 * m.eta;
    ASSERT_NEAR(k.A_jensen, (1.0 + fdr) / (1.0 - fdr), 1e-12);
    const double expected =
        normalTransmittance(m.eta) * in.irradiance[c] * jensenTotalRd(m.sigma_a[c], m.sigma_s[c], m.g[c], m.eta);
    SCOPED_TRACE(std::string(GetParam()) + " band " + std::to_string(c));
    report("standard", GetParam(), c, d.mean[c], d.standardError[c], expected);
    EXPECT_LT(d.standardError[c], 0.003 * expected);
    EXPECT_NEAR(d.mean[c], expected, 0.02 * expected);
    // Unbiased (the estimand is exactly the closed form): within 4 standard errors.
    EXPECT_NEAR(d.mean[c], expected, 4.0 * d.standardError[c]);
    EXPECT_NEAR(f.mean[c], expected, 0.02 * expected);
    // The quadrature used for the directional dipole reproduces the closed form (checks it).
    const double quad = integratePlane(
        [&](double r) { return planarSd(BssrdfModel::Standard, r, m.sigma_a[c], m.sigma_s[c], m.g[c], m.eta); },
        1e-3 * k.z_r, 60.0 / k.sigma_tr, 1.25);
    EXPECT_NEAR(kPi * quad, jensenTotalRd(m.sigma_a[c], m.sigma_s[c], m.g[c], m.eta), 1e-6);
  }
}

INSTANTIATE_TEST_SUITE_P(Materials, SlabStandardDipole, ::testing::Values("Marble", "Skimmilk", "Ketchup", "Skin1"));

class SlabDirectionalDipole : public ::testing::TestWithParam<const char*> {};

TEST_P(SlabDirectionalDipole, ConvergesToTheQuadratureOfSdOverThePlane) {
  const RadiosityMaterial m = fromTable(GetParam());
  const ScatteredRadiosityInput in = slabInput(m, BssrdfModel::Directional, 256);
  const MeanAndError d = slabEstimate<double>(in, 384);
  for (int c = 0; c < 3; ++c) {
    const BssrdfCoefficients k = bssrdfCoefficients(m.sigma_a[c], m.sigma_s[c], m.g[c], m.eta);
    const auto sd = [&](double r) {
      return planarSd(BssrdfModel::Directional, r, m.sigma_a[c], m.sigma_s[c], m.g[c], m.eta);
    };
    const double lo = 1e-4 / k.sigma_t_reduced, hi = 60.0 / k.sigma_tr;
    const double integral = integratePlane(sd, lo, hi, 1.25);
    const double finer = integratePlane(sd, 0.1 * lo, hi, 1.1);
    ASSERT_NEAR(integral, finer, 1e-5 * integral);
    // B = π E ∫ S_d F_t cos θ dA with cos θ = 1 and F_t at normal incidence.
    const double expected = kPi * in.irradiance[c] * normalTransmittance(m.eta) * integral;
    SCOPED_TRACE(std::string(GetParam()) + " band " + std::to_string(c));
    report("directional", GetParam(), c, d.mean[c], d.standardError[c], expected);
    EXPECT_LT(d.standardError[c], 0.004 * expected);
    EXPECT_NEAR(d.mean[c], expected, 0.02 * expected);
    EXPECT_NEAR(d.mean[c], expected, 4.0 * d.standardError[c]);
  }
}

INSTANTIATE_TEST_SUITE_P(Materials, SlabDirectionalDipole, ::testing::Values("Marble", "Skimmilk", "Ketchup"));

// A thick slab lit from behind (issue 17: directional lights on thick, backlit objects): x_o on the
// dark face z = 0 (n_o = −z), the light entering the face z = h (n_i = +z, light along +z). By the
// symmetry about z the estimand is π E F_t ∫ S_d(√(r² + h²)) 2πr dr, as for the front-lit slab.
// Eq. 12 alone reaches r ≈ √(h/σ_tr) rarely (heavy-tailed weights); the second density of scale
// √(h/σ_tr) (sssBacklitRadius) keeps the estimate unbiased and its spread smaller.
TEST(RadiosityEstimator, BacklitThickSlabIsUnbiasedAndTheSecondDensityCutsItsSpread) {
  const RadiosityMaterial m = fromTable("Marble");
  constexpr double h = 20.0;  // mm: σ_tr h from 2.3 (red) to 5.1 (blue)
  const LightGBufferLookup backLookup = [](const glm::dvec3& xj) {
    return std::optional<LightGBufferHit>(LightGBufferHit{{xj.x, xj.y, h}, {0.0, 0.0, 1.0}});
  };
  ScatteredRadiosityInput in = slabInput(m, BssrdfModel::Standard, 16);
  in.no = {0, 0, -1};
  const auto estimate = [&](double share) {
    in.pointShare = share;
    glm::dvec3 sum(0.0), sum2(0.0);
    constexpr int kTexels = 2000;
    for (int t = 0; t < kTexels; ++t) {
      in.texelX = static_cast<std::uint32_t>(t);
      in.texelY = 5;
      const glm::dvec3 b = estimateScatteredRadiosity<double>(in, backLookup).B;
      sum += b;
      sum2 += b * b;
    }
    MeanAndError out;
    out.mean = sum / double(kTexels);
    out.standardError = glm::sqrt(glm::max((sum2 - sum * sum / double(kTexels)) / double(kTexels - 1), glm::dvec3(0.0)) /
                                  double(kTexels));
    return out;
  };
  const MeanAndError eq12 = estimate(0.0), mixed = estimate(0.25);
  for (int c = 0; c < 3; ++c) {
    const BssrdfCoefficients k = bssrdfCoefficients(m.sigma_a[c], m.sigma_s[c], m.g[c], m.eta);
    const auto sd = [&](double r) {
      BssrdfConfig config{{r, 0.0, h}, {0, 0, 1}, {0, 0, 1}, {0, 0, 0}, {0, 0, -1},
                          m.sigma_a[c], m.sigma_s[c], m.g[c], m.eta};
      return evaluateBssrdf<double>(BssrdfModel::Standard, config).sdClamped;
    };
    const double integral = integratePlane(sd, 0.05 * h, h + 60.0 / k.sigma_tr, 1.1);
    const double expected = kPi * in.irradiance[c] * normalTransmittance(m.eta) * integral;
    std::printf("  backlit slab h = %g mm band %d (σ_tr h = %.2f): expected %.4e; Eq. 12 %.4e ± %.1e, mixed %.4e ± %.1e\n",
                h, c, k.sigma_tr * h, expected, eq12.mean[c], eq12.standardError[c], mixed.mean[c],
                mixed.standardError[c]);
    EXPECT_NEAR(eq12.mean[c], expected, 4.0 * eq12.standardError[c]) << "band " << c;
    EXPECT_NEAR(mixed.mean[c], expected, 4.0 * mixed.standardError[c]) << "band " << c;
    EXPECT_LT(mixed.standardError[c], 0.05 * expected) << "band " << c;
    // Measured 0.59, 0.65 and 0.76 of Eq. 12's spread at the same N.
    EXPECT_LT(mixed.standardError[c], 0.9 * eq12.standardError[c]) << "band " << c;
  }
  EXPECT_GT(backlitRadius(h, 0.2), 0.0);
  EXPECT_EQ(backlitRadius(4.0, 0.2), 0.0) << "σ_tr h ≤ 1: Eq. 12 alone";
  EXPECT_NEAR(backlitRadius(20.0, 0.2), 0.5 * 10.0, 1e-12);
}

TEST(RadiosityEstimator, FloatAndDoubleDrawTheSameSamples) {
  ScatteredRadiosityInput in = slabInput(fromTable("Marble"), BssrdfModel::Directional, 64);
  in.texelX = 17;
  in.frame = 3;
  const ScatteredRadiosity f = estimateScatteredRadiosity<float>(in, planeLookup);
  const ScatteredRadiosity d = estimateScatteredRadiosity<double>(in, planeLookup);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(f.B[c], d.B[c], 1e-3 * d.B[c]) << c;
}

TEST(RadiosityEstimator, PerTexelStandardErrorMatchesTheSpreadOfEstimates) {
  const ScatteredRadiosityInput in = slabInput(fromTable("Skimmilk"), BssrdfModel::Standard, 256);
  const MeanAndError spread = slabEstimate<double>(in, 400);
  ScatteredRadiosityInput one = in;
  one.texelX = 1000;
  const ScatteredRadiosity b = estimateScatteredRadiosity<double>(one, planeLookup);
  // The spread of 400 estimates × √400 is the per-estimate standard deviation.
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(b.standardError[c], spread.standardError[c] * 20.0, 0.35 * b.standardError[c]);
}

TEST(RadiosityEstimator, MissesAndBackFacingHitsContributeNothing) {
  ScatteredRadiosityInput in = slabInput(fromTable("Marble"), BssrdfModel::Directional, 32);
  const auto miss = [](const glm::dvec3&) -> std::optional<LightGBufferHit> { return std::nullopt; };
  EXPECT_EQ(estimateScatteredRadiosity<double>(in, miss).B, glm::dvec3(0.0));
  const auto back = [](const glm::dvec3& xj) -> std::optional<LightGBufferHit> {
    return LightGBufferHit{xj, {0.0, 0.0, -1.0}};
  };
  EXPECT_EQ(estimateScatteredRadiosity<double>(in, back).B, glm::dvec3(0.0));
  in.samples = 0;
  EXPECT_THROW(estimateScatteredRadiosity<double>(in, planeLookup), std::invalid_argument);
  in.samples = 4;
  in.material.g = glm::dvec3(1.0);
  EXPECT_THROW(estimateScatteredRadiosity<double>(in, planeLookup), std::invalid_argument);
}

TEST(RadiosityEstimator, SamplesPlanarPointsInTheGivenBasis) {
  ScatteredRadiosityInput in = slabInput(fromTable("Ketchup"), BssrdfModel::Standard, 4000);
  in.xo = {1.0, 2.0, 3.0};
  in.t1 = glm::normalize(glm::dvec3(1.0, 1.0, 0.0));
  in.t2 = glm::dvec3(0.0, 0.0, 1.0);
  const glm::dvec3 normal = glm::cross(in.t1, in.t2);
  std::vector<double> radii;
  const auto record = [&](const glm::dvec3& xj) -> std::optional<LightGBufferHit> {
    EXPECT_NEAR(glm::dot(xj - in.xo, normal), 0.0, 1e-9);
    radii.push_back(glm::length(xj - in.xo));
    return std::nullopt;
  };
  estimateScatteredRadiosity<double>(in, record);
  ASSERT_EQ(radii.size(), 4000u);  // one look-up per sample, shared by the bands
  // The sampling rate is σ_tr of Eq. 10 wherever σ_a > 0 (the bound only acts without absorption).
  for (int c = 0; c < 3; ++c) {
    const double sigmaTr = bssrdfCoefficients(in.material.sigma_a[c], in.material.sigma_s[c], 0.0, 1.3).sigma_tr;
    EXPECT_DOUBLE_EQ(samplingSigmaTr(in.material.sigma_a[c], in.material.sigma_s[c], 0.0, 1.3), sigmaTr);
  }
}

// --- Random numbers ---------------------------------------------------------------------------

TEST(RadiosityRandom, PcgHashNestingMatchesValuesComputedIndependently) {
  // Computed with Python's unbounded integers reduced mod 2³² (O'Neill's PCG step and RXS-M-XS
  // output, nested h(x + h(y + …h(dim)))).
  EXPECT_EQ(radiosityRandomBits({0, 0, 0, 0, 0, 0, 0}), 2705626233u);
  EXPECT_EQ(radiosityRandomBits({3, 5, 7, 11, 2, 1000, 1}), 572953411u);
  EXPECT_EQ(radiosityRandomBits({0xffffffffu, 0xfffffffeu, 9, 123456, 1, 999999, 0}), 2652516580u);
}

/// χ²_p quantile for k degrees of freedom, Wilson and Hilferty (1931): k (1 − 2/(9k) + z √(2/(9k)))³,
/// z the standard normal quantile; accurate to < 0.5% at k = 63.
double chiSquareQuantile(int k, double z) {
  const double a = 2.0 / (9.0 * k);
  return k * std::pow(1.0 - a + z * std::sqrt(a), 3.0);
}

template <class Next>
double chiSquare64(int n, const Next& next) {
  std::vector<int> bins(64, 0);
  for (int i = 0; i < n; ++i) {
    const double xi = next(i);
    EXPECT_GE(xi, 0.0);
    EXPECT_LT(xi, 1.0);
    ++bins[size_t(xi * 64.0)];
  }
  const double expected = n / 64.0;
  double chi2 = 0.0;
  for (int b : bins) chi2 += (b - expected) * (b - expected) / expected;
  return chi2;
}

TEST(RadiosityRandom, UniformAlongEveryCoordinate) {
  const int n = 100000;
  const double threshold = chiSquareQuantile(63, 3.0902);  // p = 0.001: ≈ 103.4
  EXPECT_NEAR(threshold, 103.4, 0.5);
  const auto along = [&](int coordinate) {
    return chiSquare64(n, [&](int i) {
      RandomStreamId id{12, 34, 2, 5, 1, 77, 0};
      const auto u = static_cast<std::uint32_t>(i);
      switch (coordinate) {
        case 0: id.sample = u; break;
        case 1: id.x = u % 1000; id.y = u / 1000; break;
        case 2: id.frame = u; break;
        case 3: id.map = u % 16; id.band = u / 16 % 3; id.dim = u / 48; break;
      }
      return radiosityRandom<double>(id);
    });
  };
  for (int coordinate = 0; coordinate < 4; ++coordinate) EXPECT_LT(along(coordinate), threshold) << coordinate;
}

TEST(RadiosityRandom, StreamsAreDistinctAndUncorrelated) {
  const RandomStreamId base{5, 6, 1, 9, 0, 0, 0};
  std::vector<RandomStreamId> streams{base};
  for (int field = 0; field < 6; ++field) {
    RandomStreamId s = base;
    switch (field) {
      case 0: s.x += 1; break;
      case 1: s.y += 1; break;
      case 2: s.map += 1; break;
      case 3: s.frame += 1; break;
      case 4: s.band += 1; break;
      case 5: s.dim += 1; break;
    }
    streams.push_back(s);
  }
  // Swapped coordinates are different streams too.
  streams.push_back({6, 5, 1, 9, 0, 0, 0});
  const int n = 20000;
  std::vector<std::vector<double>> seq(streams.size());
  for (size_t s = 0; s < streams.size(); ++s)
    for (int j = 0; j < n; ++j) {
      RandomStreamId id = streams[s];
      id.sample = static_cast<std::uint32_t>(j);
      seq[s].push_back(radiosityRandom<double>(id));
    }
  for (size_t a = 0; a < seq.size(); ++a)
    for (size_t b = a + 1; b < seq.size(); ++b) {
      int equal = 0;
      double ma = 0, mb = 0, cab = 0, va = 0, vb = 0;
      for (int j = 0; j < n; ++j) {
        equal += seq[a][size_t(j)] == seq[b][size_t(j)];
        ma += seq[a][size_t(j)] / n;
        mb += seq[b][size_t(j)] / n;
      }
      for (int j = 0; j < n; ++j) {
        const double da = seq[a][size_t(j)] - ma, db = seq[b][size_t(j)] - mb;
        cab += da * db;
        va += da * da;
        vb += db * db;
      }
      // Equal 24-bit values happen by chance with probability 2⁻²⁴ per pair.
      EXPECT_LE(equal, 1) << a << " " << b;
      EXPECT_LT(std::abs(cab / std::sqrt(va * vb)), 4.5 / std::sqrt(double(n))) << a << " " << b;
    }
}

TEST(RadiosityRandom, FloatAndDoubleGiveIdenticalBits) {
  for (std::uint32_t i = 0; i < 200000; ++i) {
    const RandomStreamId id{i % 640, i / 640, i % 7, i * 2654435761u, i % 3, i, i % 2};
    const float f = radiosityRandom<float>(id);
    const double d = radiosityRandom<double>(id);
    ASSERT_EQ(static_cast<double>(f), d) << i;
    ASSERT_EQ(d, double(radiosityRandomBits(id) >> 8) / 16777216.0) << i;
  }
}

// --- Halton directions ------------------------------------------------------------------------

TEST(HaltonDirection, RadicalInversesByHand) {
  // Base 2: 1 → .1, 2 → .01, 3 → .11, 4 → .001, 5 → .101, 6 → .011.
  const double base2[] = {0.5, 0.25, 0.75, 0.125, 0.625, 0.375};
  // Base 3: 1 → .1, 2 → .2, 3 → .01, 4 → .11, 5 → .21, 9 → .001.
  const double base3[] = {1.0 / 3, 2.0 / 3, 1.0 / 9, 4.0 / 9, 7.0 / 9};
  for (std::uint32_t i = 1; i <= 6; ++i) EXPECT_DOUBLE_EQ(radicalInverse(i, 2), base2[i - 1]) << i;
  for (std::uint32_t i = 1; i <= 5; ++i) EXPECT_NEAR(radicalInverse(i, 3), base3[i - 1], 1e-15) << i;
  EXPECT_NEAR(radicalInverse(9, 3), 1.0 / 27, 1e-15);
  EXPECT_EQ(radicalInverse(0, 2), 0.0);
}

TEST(HaltonDirection, FirstDirectionsFromTheRadicalInverses) {
  // k → (u, v) = (Φ₂(k+1), Φ₃(k+1)) → z = 1 − 2u, φ = 2πv.
  struct Case {
    std::uint32_t k;
    double u, v;
  } cases[] = {{0, 0.5, 1.0 / 3}, {1, 0.25, 2.0 / 3}, {2, 0.75, 1.0 / 9}, {3, 0.125, 4.0 / 9}};
  for (const Case& c : cases) {
    const double z = 1.0 - 2.0 * c.u, rho = std::sqrt(1.0 - z * z), phi = 2.0 * kPi * c.v;
    const glm::dvec3 expected(rho * std::cos(phi), rho * std::sin(phi), z);
    for (int p = 0; p < 2; ++p) {
      const glm::dvec3 d = p ? haltonDirection<float>(c.k) : haltonDirection<double>(c.k);
      const double tol = p ? 1e-6 : 1e-14;
      EXPECT_NEAR(d.x, expected.x, tol) << c.k;
      EXPECT_NEAR(d.y, expected.y, tol) << c.k;
      EXPECT_NEAR(d.z, expected.z, tol) << c.k;
    }
  }
  // k = 0 by hand: z = 0, φ = 120°.
  const glm::dvec3 d0 = haltonDirection<double>(0);
  EXPECT_NEAR(d0.x, -0.5, 1e-15);
  EXPECT_NEAR(d0.y, std::sqrt(3.0) / 2.0, 1e-15);
  EXPECT_NEAR(d0.z, 0.0, 1e-15);
}

TEST(HaltonDirection, UnitLengthAndCoverage) {
  glm::dvec3 mean(0.0);
  std::set<std::pair<long, long>> distinct;
  for (std::uint32_t k = 0; k < 256; ++k) {
    const glm::dvec3 d = haltonDirection<double>(k);
    EXPECT_NEAR(glm::length(d), 1.0, 1e-12) << k;
    EXPECT_NEAR(glm::length(haltonDirection<float>(k)), 1.0, 1e-6) << k;
    mean += d / 256.0;
    distinct.insert({std::lround(d.x * 1e6), std::lround(d.z * 1e6)});
  }
  EXPECT_EQ(distinct.size(), 256u);
  std::printf("  |mean of 256 Halton directions| = %.5f\n", glm::length(mean));
  // 256 independent uniform directions would give |mean| ≈ 1/16; the low-discrepancy set does far better.
  EXPECT_LT(glm::length(mean), 0.01);
  // Every octant is populated about equally (32 each).
  int octants[8] = {};
  for (std::uint32_t k = 0; k < 256; ++k) {
    const glm::dvec3 d = haltonDirection<double>(k);
    ++octants[(d.x > 0) + 2 * (d.y > 0) + 4 * (d.z > 0)];
  }
  for (int o : octants) EXPECT_NEAR(o, 32, 6);
}

// --- Stereographic correction (Eqs. 13–14) --------------------------------------------------

// --- Point lights' second distance density and the mixture (issue 17) ------------------------------

/// ∫_a^b f by Simpson's rule with n (even) panels.
template <class F>
double simpson(const F& f, double a, double b, int n) {
  const double h = (b - a) / n;
  double sum = f(a) + f(b);
  for (int i = 1; i < n; ++i) sum += (i % 2 ? 4.0 : 2.0) * f(a + i * h);
  return sum * h / 3.0;
}

/// ∫ over α and over r ∈ [r(t0), r(t1)] of p₂(r, α), through t = r/(r + R) ∈ [0, 1), which maps the
/// density's r⁻³ tail onto a finite interval (dr = R/(1 − t)² dt).
double stereoMass(double t0, double t1, double radius) {
  return simpson([&](double t) {
    if (t >= 1.0) return 0.0;  // the integrand tends to 0 there (4(1 − t)/(π t³) · 2π)
    const double r = radius * t / (1.0 - t);
    return 2.0 * kPi * stereoRadialPdf(r, radius) * radius / ((1.0 - t) * (1.0 - t));
  }, t0, t1, 2000);
}

TEST(StereoDensity, IntegratesToOneOverThePlane) {
  for (const double radius : {0.01, 1.0, 37.0}) EXPECT_NEAR(stereoMass(0.0, 1.0, radius), 1.0, 1e-6) << radius;
}

TEST(StereoDensity, SampledDistancesFollowItsPdf) {
  // 20 bins of equal width in t = r/(r + R); expected counts from the quadrature of the pdf, observed
  // ones from r = 2R √(ξ/(1 − ξ)) with ξ from the estimator's random streams.
  constexpr int kBins = 20, kSamples = 200000;
  const double radius = 2.0;
  std::vector<int> counts(kBins, 0);
  for (int j = 0; j < kSamples; ++j) {
    const RandomStreamId id{static_cast<std::uint32_t>(j % 512), static_cast<std::uint32_t>(j / 512), 3, 7, 0, 0, 0};
    const double r = sampleStereoRadius(radiosityRandom<double>(id), radius);
    ++counts[std::min(kBins - 1, static_cast<int>(r / (r + radius) * kBins))];
  }
  double chi2 = 0.0;
  for (int b = 0; b < kBins; ++b) {
    const double expected = kSamples * stereoMass(double(b) / kBins, double(b + 1) / kBins, radius);
    chi2 += (counts[b] - expected) * (counts[b] - expected) / expected;
  }
  EXPECT_LT(chi2, 43.82);  // χ² with 19 degrees of freedom at p = 0.001
}

TEST(MixtureSampling, WithoutTheSecondDensityAndOneRateItIsEq11) {
  // Eq. 11's p(r, α) = σ_tr e^{−σ_tr r}/(2π), computed here; three equal rates average to it.
  for (const double r : {0.0, 0.3, 4.0, 11.0}) {
    const double eq11 = 0.8 * std::exp(-0.8 * r) / (2.0 * kPi);
    EXPECT_NEAR(bandMixturePdf(r, glm::dvec3(0.8), 5.0, 0.0), eq11, 1e-12 * eq11) << r;
    const double mixed = (eq11 + 0.2 * std::exp(-0.2 * r) / (2.0 * kPi) + 3.0 * std::exp(-3.0 * r) / (2.0 * kPi)) / 3.0;
    EXPECT_NEAR(bandMixturePdf(r, {0.8, 0.2, 3.0}, 5.0, 0.0), mixed, 1e-12 * mixed) << r;
  }
}

TEST(MixtureSampling, UnbiasedForAFarReachingIntegrandWhereEq12AloneIsNot) {
  // f = (1 + r²/L²)⁻² per unit area of the plane: ∫ f dA = π L². With 1/σ_tr = 0.5 mm, Eq. 12's
  // samples stop at 16.6/σ_tr = 8.3 mm, beyond which lies 1/(1 + 8.3²/L²) = 85% of ∫ f for L = 20 mm:
  // the light a point light's far wax gives (the candle's lower wall), which Eq. 12 alone misses.
  const double L = 20.0, sigmaTr = 2.0, radius = 10.0, exact = kPi * L * L;
  const glm::dvec3 xo(1.0, -2.0, 0.5), t1(1.0, 0.0, 0.0), t2(0.0, 1.0, 0.0);
  constexpr int kSamples = 200000;
  const auto estimate = [&](double share, double& standardError) {
    double sum = 0.0, sumSquares = 0.0;
    for (int j = 0; j < kSamples; ++j) {
      const RandomStreamId id{static_cast<std::uint32_t>(j % 256), static_cast<std::uint32_t>(j / 256), 1, 2, 0, 0, 0};
      const PlanarSample s = drawSharedSample<double>(xo, t1, t2, glm::dvec3(sigmaTr), radius, share, id, 1u);
      EXPECT_NEAR(glm::length(s.xj - xo), s.r, 1e-9 * (1.0 + s.r));
      const double q = 1.0 + s.r * s.r / (L * L);
      const double v = s.weight / (q * q);
      sum += v;
      sumSquares += v * v;
    }
    const double mean = sum / kSamples;
    standardError = std::sqrt(std::max(0.0, sumSquares / kSamples - mean * mean) / kSamples);
    return mean;
  };
  for (const double share : {0.1, 0.25, 0.5, 0.9}) {
    double se = 0.0;
    const double m = estimate(share, se);
    std::printf("[ mis ] share %.2f: %.2f ± %.2f (exact %.2f)\n", share, m, se, exact);
    EXPECT_LT(se, 0.02 * exact) << share;
    EXPECT_NEAR(m, exact, 4.0 * se) << share;
  }
  double se = 0.0;
  EXPECT_LT(estimate(0.0, se), 0.2 * exact);  // Eq. 12 alone: the 85% beyond its reach is lost
}

TEST(MixtureSampling, FloatAndDoubleDrawTheSameDistances) {
  const glm::dvec3 xo(0.0), t1(1.0, 0.0, 0.0), t2(0.0, 0.0, 1.0);
  for (std::uint32_t j = 0; j < 2000; ++j) {
    const RandomStreamId id{j, 5, 0, 1, 2, j % 7, 0};
    const PlanarSample f = drawSharedSample<float>(xo, t1, t2, {0.6, 0.1, 2.5}, 12.0, 0.25, id, 7u);
    const PlanarSample d = drawSharedSample<double>(xo, t1, t2, {0.6, 0.1, 2.5}, 12.0, 0.25, id, 7u);
    EXPECT_NEAR(f.r, d.r, 1e-5 * (1.0 + d.r)) << j;
    EXPECT_NEAR(f.weight, d.weight, 1e-4 * (1.0 + d.weight)) << j;
  }
}

// --- One sample pattern for the three bands (issue 17) -------------------------------------------

/// ∫ over α and r ∈ [r(t0), r(t1)] of p_mix(r, α), through t = r/(r + R) as stereoMass.
double mixtureMass(double t0, double t1, const glm::dvec3& sigmaTr, double radius, double share) {
  return simpson([&](double t) {
    if (t >= 1.0) return 0.0;
    const double r = radius * t / (1.0 - t);
    return 2.0 * kPi * bandMixturePdf(r, sigmaTr, radius, share) * radius / ((1.0 - t) * (1.0 - t));
  }, t0, t1, 4000);
}

TEST(SharedSampling, MixtureIntegratesToOne) {
  for (const double share : {0.0, 0.3, 0.9})
    EXPECT_NEAR(mixtureMass(0.0, 1.0, {0.8, 0.2, 3.0}, 5.0, share), 1.0, 1e-6) << share;
}

TEST(SharedSampling, DrawnDistancesFollowTheMixturePdf) {
  // 20 bins of equal width in t = r/(r + R), expected counts by quadrature of p_mix, observed ones
  // drawn as the gather draws them (5 samples per texel: the picks stratified within a texel).
  constexpr int kBins = 20, kSamples = 200000, kPerTexel = 5;
  const glm::dvec3 sigmaTr(0.8, 0.2, 3.0);
  const glm::dvec3 xo(0.0), t1(1.0, 0.0, 0.0), t2(0.0, 1.0, 0.0);
  for (const double share : {0.0, 0.3}) {
    const double radius = 4.0;
    std::vector<int> counts(kBins, 0);
    for (int i = 0; i < kSamples; ++i) {
      const int texel = i / kPerTexel;
      const RandomStreamId id{static_cast<std::uint32_t>(texel % 400), static_cast<std::uint32_t>(texel / 400), 2, 9,
                              0, static_cast<std::uint32_t>(i % kPerTexel), 0};
      const double r = drawSharedSample<double>(xo, t1, t2, sigmaTr, radius, share, id, kPerTexel).r;
      ++counts[std::min(kBins - 1, static_cast<int>(r / (r + radius) * kBins))];
    }
    double chi2 = 0.0;
    for (int b = 0; b < kBins; ++b) {
      const double expected = kSamples * mixtureMass(double(b) / kBins, double(b + 1) / kBins, sigmaTr, radius, share);
      chi2 += (counts[b] - expected) * (counts[b] - expected) / expected;
    }
    EXPECT_LT(chi2, 43.82) << share;  // χ² with 19 degrees of freedom at p = 0.001
  }
}

/// Pearson's correlation of the errors of bands a and b over estimates at `texels` texels.
double bandErrorCorrelation(ScatteredRadiosityInput in, int texels, int a, int b) {
  std::vector<glm::dvec3> values;
  glm::dvec3 mean(0.0);
  for (int t = 0; t < texels; ++t) {
    in.texelX = static_cast<std::uint32_t>(t);
    values.push_back(estimateScatteredRadiosity<double>(in, planeLookup).B);
    mean += values.back() / double(texels);
  }
  double sab = 0.0, saa = 0.0, sbb = 0.0;
  for (const glm::dvec3& v : values) {
    const glm::dvec3 e = v - mean;
    sab += e[a] * e[b], saa += e[a] * e[a], sbb += e[b] * e[b];
  }
  return sab / std::sqrt(saa * sbb);
}

TEST(SharedSampling, TheBandsErrorsAreCorrelatedGreyNoise) {
  // Every band sees the same x_j: positively correlated errors, which a pixel shows as a change of
  // brightness rather than of hue (§3.1's own stream per band would give |ρ| within 3/√texels of 0).
  constexpr int kTexels = 600;
  ScatteredRadiosityInput in = slabInput(fromTable("Marble"), BssrdfModel::Directional, 4);
  for (const auto& [a, b] : {std::pair{0, 1}, std::pair{1, 2}, std::pair{0, 2}}) {
    const double shared = bandErrorCorrelation(in, kTexels, a, b);
    std::printf("[ bands ] Marble, N = 4: ρ(%d, %d) shared %+.3f\n", a, b, shared);
    EXPECT_GT(shared, 0.5) << a << b;
  }
}

TEST(SharedSampling, DistancesComeFromTheMixtureOfTheBandsRates) {
  ScatteredRadiosityInput in = slabInput(fromTable("Ketchup"), BssrdfModel::Standard, 3000);
  std::vector<double> radii;
  const auto record = [&](const glm::dvec3& xj) -> std::optional<LightGBufferHit> {
    radii.push_back(glm::length(xj - in.xo));
    return std::nullopt;
  };
  estimateScatteredRadiosity<double>(in, record);
  ASSERT_EQ(radii.size(), 3000u);  // one look-up per sample for the three bands
  // The picks are stratified, so exactly 1000 samples come from each band's Eq. 12: the mean is the
  // average of the bands' means 1/σ_tr, within 4 standard errors.
  double expected = 0.0, mean = 0.0, meanSquare = 0.0;
  for (int c = 0; c < 3; ++c)
    expected += 1.0 / samplingSigmaTr(in.material.sigma_a[c], in.material.sigma_s[c], 0.0, 1.3) / 3.0;
  for (const double r : radii) mean += r / 3000.0, meanSquare += r * r / 3000.0;
  EXPECT_NEAR(mean, expected, 4.0 * std::sqrt((meanSquare - mean * mean) / 3000.0));
}

TEST(StereographicLookup, ZeroOffsetLooksUpAlongXoMinusXl) {
  // r → 0: ℓ = ((x_o − x_ℓ) − (x_ℓ − x_o))/‖·‖ = −a/‖a‖ with a = x_ℓ − x_o, so
  // x_stereo − x_ℓ = a − 2(a·(−â))(−â) = a − 2a = x_o − x_ℓ (the planar direction).
  const glm::dvec3 xl(0.3, -1.2, 2.0);
  for (int i = 0; i < 20; ++i) {
    const glm::dvec3 dir = haltonDirection<double>(std::uint32_t(i));
    const double R = 0.5 + i;
    const glm::dvec3 xo = xl + R * dir;
    const glm::dvec3 d = stereographicLookupDirection<double>(xo, xo, xl);
    EXPECT_NEAR(glm::length(d - (xo - xl)), 0.0, 1e-12 * R) << i;
    EXPECT_NEAR(glm::length(planarLookupDirection(xo, xl) - (xo - xl)), 0.0, 1e-15 * R);
    EXPECT_NEAR(glm::length(stereographicLookupDirection<float>(xo, xo, xl) - (xo - xl)), 0.0, 1e-5 * R) << i;
  }
}

TEST(StereographicLookup, HandComputedCase) {
  // Light at the origin, x_o = (0, 0, 1), x_j = (1, 0, 1) (r = 1 in the tangent plane z = 1).
  // a = (0, 0, −1); (x_j − x_ℓ) − a = (1, 0, 2); ℓ = (1, 0, 2)/√5; a·ℓ = −2/√5;
  // x_stereo − x_ℓ = (0, 0, −1) + (4/5)(1, 0, 2) = (0.8, 0, 0.6): the unit sphere's point on the
  // line from the antipode (0, 0, −1) through x_j (t = 0.8 on (t, 0, 2t − 1)).
  const glm::dvec3 d = stereographicLookupDirection<double>({0, 0, 1}, {1, 0, 1}, {0, 0, 0});
  EXPECT_NEAR(d.x, 0.8, 1e-15);
  EXPECT_NEAR(d.y, 0.0, 1e-15);
  EXPECT_NEAR(d.z, 0.6, 1e-15);
  const glm::dvec3 p = planarLookupDirection({1, 0, 1}, {0, 0, 0});
  EXPECT_EQ(p, glm::dvec3(1, 0, 1));
}

// dA_i/dA_j of both look-ups against finite differences: x_j moves by h along two axes of x_o's
// tangent plane, each position is looked up (the ray from x_ℓ along the look-up direction meets a
// sphere of radius 4 centred away from the light, as the inside of a cup), and the parallelogram
// of the two displaced x_i over h² is the area ratio. Tangent planes tilted against x_ℓ − x_o.
TEST(PointLightAreaRatio, MatchesFiniteDifferencesOfTheLookUp) {
  const glm::dvec3 centre(0.3, 0.1, -0.2), xl(0.0, 0.0, 0.0);
  const double radius = 4.0;
  const auto onSphere = [&](const glm::dvec3& dir) {  // the ray x_l + t·dir, t > 0, x_l inside
    const glm::dvec3 d = glm::normalize(dir), oc = xl - centre;
    const double b = glm::dot(oc, d), c = glm::dot(oc, oc) - radius * radius;
    return xl + (-b + std::sqrt(b * b - c)) * d;
  };
  int checked = 0;
  for (std::uint32_t i = 0; i < 24; ++i) {
    const glm::dvec3 xo = onSphere(haltonDirection<double>(i));
    const glm::dvec3 no = glm::normalize(centre - xo);  // the cup's inner wall faces its centre
    const glm::dvec3 t1 = glm::normalize(glm::cross(no, std::abs(no.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
    const glm::dvec3 t2 = glm::cross(no, t1);
    const glm::dvec3 xj = xo + (0.1 + 0.25 * (i % 7)) * glm::normalize(std::cos(0.7 * i) * t1 + std::sin(0.7 * i) * t2);
    for (const bool stereographic : {false, true}) {
      const auto lookUp = [&](const glm::dvec3& p) {
        return onSphere(stereographic ? stereographicLookupDirection<double>(xo, p, xl) : planarLookupDirection(p, xl));
      };
      const double h = 1e-5;
      const glm::dvec3 du = (lookUp(xj + h * t1) - lookUp(xj - h * t1)) / (2.0 * h);
      const glm::dvec3 dv = (lookUp(xj + h * t2) - lookUp(xj - h * t2)) / (2.0 * h);
      const double numeric = glm::length(glm::cross(du, dv));
      const glm::dvec3 xi = lookUp(xj), ni = glm::normalize(centre - xi);
      const double ratio = stereographic ? stereographicAreaRatio(xo, no, xj, xl, xi, ni)
                                         : planarAreaRatio(no, xj, xl, xi, ni);
      EXPECT_NEAR(ratio / numeric, 1.0, 1e-6) << "sample " << i << (stereographic ? " stereographic" : " planar");
      ++checked;
    }
  }
  // x_j = x_o with the tangent plane normal to x_l − x_o: both look-ups are the identity to first order.
  const glm::dvec3 xo(0, 0, 2), no(0, 0, -1);
  EXPECT_NEAR(stereographicAreaRatio(xo, no, xo, xl, xo, no), 1.0, 1e-12);
  EXPECT_NEAR(planarAreaRatio(no, xo, xl, xo, no), 1.0, 1e-12);
  EXPECT_EQ(checked, 48);
}

TEST(StereographicLookup, IsTheInverseStereographicProjectionFromTheAntipode) {
  const glm::dvec3 xl(1.0, 2.0, -0.5);
  for (std::uint32_t i = 0; i < 50; ++i) {
    const glm::dvec3 xo = xl + (1.0 + 0.1 * i) * haltonDirection<double>(i);
    const glm::dvec3 xj = xo + (0.2 + 0.3 * i) * glm::normalize(haltonDirection<double>(i + 100) - 0.3 * (xo - xl));
    const glm::dvec3 a = xl - xo, antipode = xl + a;
    const glm::dvec3 s = stereographicLookupDirection<double>(xo, xj, xl);
    EXPECT_NEAR(glm::length(s), glm::length(a), 1e-12 * glm::length(a)) << i;  // on the sphere
    const glm::dvec3 u = glm::normalize(xj - antipode), v = glm::normalize(xl + s - antipode);
    EXPECT_NEAR(glm::length(glm::cross(u, v)), 0.0, 1e-9) << i;  // on the line antipode → x_j
  }
  // Far samples approach the antipode direction a.
  const glm::dvec3 far = stereographicLookupDirection<double>({0, 0, 1}, {1e6, 0, 1}, {0, 0, 0});
  EXPECT_NEAR(far.z, -1.0, 1e-5);
  // Degenerate inputs stay finite: x_o at the light, x_j at the antipode.
  const glm::dvec3 atLight = stereographicLookupDirection<double>({0, 0, 0}, {1, 0, 0}, {0, 0, 0});
  EXPECT_EQ(atLight, glm::dvec3(1, 0, 0));
  const glm::dvec3 atAntipode = stereographicLookupDirection<float>({0, 0, 1}, {0, 0, -1}, {0, 0, 0});
  EXPECT_EQ(atAntipode, glm::dvec3(0, 0, -1));
}

// --- Robustness -------------------------------------------------------------------------------

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

template <class Real>
void expectFiniteEverywhere(const char* precision) {
  SCOPED_TRACE(precision);
  for (BssrdfModel model : {BssrdfModel::Standard, BssrdfModel::Directional, BssrdfModel::PhotonBeamDiffusion}) {
    SCOPED_TRACE(std::string(bssrdfModelName(model)));
    const int n = model == BssrdfModel::PhotonBeamDiffusion ? 8 : 64;
    // σ_a = 0 (σ_tr = 0), and σ_a = 10⁻³⁰: the sampling rate falls back to 10⁻³ σ_t'.
    for (double sa : {0.0, 1e-30}) {
      ScatteredRadiosityInput in = slabInput(fromTable("Spectralon"), model, n);
      in.material.sigma_a = glm::dvec3(sa);
      EXPECT_DOUBLE_EQ(samplingSigmaTr(sa, 11.6, 0.0, 1.3), 1e-3 * 11.6);
      const ScatteredRadiosity b = estimateScatteredRadiosity<Real>(in, planeLookup);
      EXPECT_TRUE(finite(b.B) && finite(b.standardError));
      EXPECT_GE(glm::min(b.B.x, glm::min(b.B.y, b.B.z)), 0.0);
    }
    // Thin media: σ_t' = 2·10⁻⁶ mm⁻¹ puts samples kilometres away (r ≈ 10⁷ mm).
    {
      ScatteredRadiosityInput in = slabInput({}, model, n);
      in.material.sigma_a = glm::dvec3(1e-6);
      in.material.sigma_s = glm::dvec3(1e-6);
      const ScatteredRadiosity b = estimateScatteredRadiosity<Real>(in, planeLookup);
      EXPECT_TRUE(finite(b.B) && finite(b.standardError));
    }
    // x_i far from x_o (r huge) whatever x_j is: the texel saw a surface 100 m up the light's view
    // (x_i keeps x_j's place across the view and takes the texel's plane, as on the GPU).
    {
      ScatteredRadiosityInput in = slabInput(fromTable("Marble"), model, n);
      const auto farAway = [](const glm::dvec3& xj) -> std::optional<LightGBufferHit> {
        return LightGBufferHit{xj + glm::dvec3(0, 0, 1e5), {0, 0, 1}};
      };
      const ScatteredRadiosity b = estimateScatteredRadiosity<Real>(in, farAway);
      EXPECT_TRUE(finite(b.B));
      EXPECT_LT(b.B.x, 1e-30);
    }
    // Grazing light: cos θ_ℓ = 10⁻⁷ and exactly 0, for η > 1 and η < 1 (total internal
    // reflection beyond 44° for η = 0.7).
    for (double eta : {1.3, 0.7, 0.5}) {
      for (double cosL : {1e-7, 0.0, 0.5, 0.9}) {
        ScatteredRadiosityInput in = slabInput(fromTable("Skimmilk"), model, n);
        in.material.eta = eta;
        in.toLight = {std::sqrt(1.0 - cosL * cosL), 0.0, cosL};
        const ScatteredRadiosity b = estimateScatteredRadiosity<Real>(in, planeLookup);
        EXPECT_TRUE(finite(b.B) && finite(b.standardError)) << eta << " " << cosL;
        EXPECT_GE(glm::min(b.B.x, glm::min(b.B.y, b.B.z)), 0.0);
        if (cosL == 0.0) {
          EXPECT_EQ(b.B, glm::dvec3(0.0));
        }
        // Beyond the critical angle nothing enters: F_t = 0 for every model.
        if (eta < 1.0 && cosL < std::sqrt(1.0 - eta * eta)) {
          EXPECT_EQ(b.B, glm::dvec3(0.0)) << eta << " " << cosL;
        }
      }
    }
  }
}

TEST(RadiosityEstimator, FiniteForZeroAbsorptionHugeDistancesGrazingLightAndEtaBelowOne) {
  expectFiniteEverywhere<double>("double");
  expectFiniteEverywhere<float>("float");
}

}  // namespace
}  // namespace tallow::sss
