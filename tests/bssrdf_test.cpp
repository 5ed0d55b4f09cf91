// The BSSRDF models without GL: Fresnel terms, the C_φ/C_E fits, the standard dipole's total
// reflectance, the directional dipole's derivation (Eqs. 9, 18, 19, 20), symmetries and Eq. 23,
// the reciprocal variant, and the photon-beam-diffusion quadrature against an independent
// integration. Formulas: docs/bssrdf-models.md.
#include "sss/bssrdf/bssrdf.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "gpu/glsl_shared.h"

// The shared model files in double, for the internals the C++ face does not expose.
namespace tallow::bssrdf_test_shared {
using namespace glm;
using real = double;
using real2 = glm::dvec2;
using real3 = glm::dvec3;
#include "sss/bssrdf/bssrdf_models.inc"
}  // namespace tallow::bssrdf_test_shared

namespace tallow::sss {
namespace {

namespace sh = bssrdf_test_shared;
using glm::dvec3;
constexpr double kPi = 3.14159265358979323846;

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

/// Adaptive Simpson quadrature with Richardson extrapolation: a different rule from the library's
/// Gauss–Kronrod (sss/bssrdf/bssrdf.cpp), so that the two integrations check each other.
double simpsonStep(const std::function<double(double)>& f, double a, double b, double fa, double fm, double fb,
                   double whole, double tol, int depth) {
  const double m = 0.5 * (a + b), lm = 0.5 * (a + m), rm = 0.5 * (m + b);
  const double flm = f(lm), frm = f(rm);
  const double left = (m - a) / 6.0 * (fa + 4.0 * flm + fm), right = (b - m) / 6.0 * (fm + 4.0 * frm + fb);
  const double delta = left + right - whole;
  // Converged to the requested absolute tolerance, or to what double rounding allows.
  const double limit = 15.0 * std::max(tol, 1e-15 * std::abs(left + right));
  if (depth >= 40 || std::abs(delta) <= limit) return left + right + delta / 15.0;
  return simpsonStep(f, a, m, fa, flm, fm, left, 0.5 * tol, depth + 1) +
         simpsonStep(f, m, b, fm, frm, fb, right, 0.5 * tol, depth + 1);
}

double integrate(const std::function<double(double)>& f, double a, double b, double tol) {
  // Start from 64 panels so that narrow features are not missed by the first estimate.
  const int n = 64;
  double total = 0.0;
  for (int i = 0; i < n; ++i) {
    const double x0 = a + (b - a) * i / n, x1 = a + (b - a) * (i + 1) / n, xm = 0.5 * (x0 + x1);
    const double f0 = f(x0), fm = f(xm), f1 = f(x1);
    total += simpsonStep(f, x0, x1, f0, fm, f1, (x1 - x0) / 6.0 * (f0 + 4.0 * fm + f1), tol / n, 0);
  }
  return total;
}

dvec3 randomUnit(std::mt19937_64& rng) {
  std::normal_distribution<double> n;
  dvec3 v(n(rng), n(rng), n(rng));
  return glm::normalize(v);
}

/// Reflection of v in the plane through the origin with unit normal p.
dvec3 mirror(const dvec3& v, const dvec3& p) { return v - 2.0 * glm::dot(v, p) * p; }

BssrdfConfig planarConfig(double x, double y, double thetaDeg, double sigmaA, double sigmaS, double g, double eta) {
  const double t = thetaDeg * kPi / 180.0;
  return BssrdfConfig{dvec3(0.0), dvec3(0, 0, 1), dvec3(-std::sin(t), 0, std::cos(t)), dvec3(x, y, 0), dvec3(0, 0, 1),
                      sigmaA, sigmaS, g, eta};
}

double sd(BssrdfModel m, const BssrdfConfig& c) { return evaluateBssrdf<double>(m, c).sd; }

// --- Names and validation ----------------------------------------------------------------------

TEST(BssrdfModel, NamesRoundTripAndUnknownNamesListTheChoices) {
  for (BssrdfModel m : {BssrdfModel::Standard, BssrdfModel::Directional, BssrdfModel::PhotonBeamDiffusion})
    EXPECT_EQ(parseBssrdfModel(bssrdfModelName(m)), m);
  EXPECT_EQ(bssrdfModelName(BssrdfModel::PhotonBeamDiffusion), "pbd");
  EXPECT_EQ(errorOf([] { parseBssrdfModel("dipole"); }),
            "unknown BSSRDF model \"dipole\" (standard, directional, pbd)");
}

TEST(BssrdfConfigValidation, RejectsEachInvalidFieldWithOneLine) {
  const BssrdfConfig ok = planarConfig(1, 0, 30, 0.01, 1.0, 0.5, 1.3);
  EXPECT_EQ(errorOf([&] { validateBssrdfConfig(ok); }), "");
  auto with = [&](auto change) {
    BssrdfConfig c = ok;
    change(c);
    return errorOf([&] { validateBssrdfConfig(c); });
  };
  EXPECT_EQ(with([](BssrdfConfig& c) { c.sigma_a = -0.5; }), "sigma_a is negative (-0.5)");
  EXPECT_EQ(with([](BssrdfConfig& c) { c.sigma_s = -1; }), "sigma_s is negative (-1)");
  EXPECT_EQ(with([](BssrdfConfig& c) { c.sigma_a = c.sigma_s = 0; }),
            "sigma_a + sigma_s is 0: the medium neither scatters nor absorbs");
  // fuzz_bssrdf_csv's find: σ_a = 0, σ_s = 1.1e-319 evaluated to NaN in every model.
  EXPECT_EQ(with([](BssrdfConfig& c) { c.sigma_a = 0, c.sigma_s = 1e-31, c.g = 0; }),
            "sigma_a + (1 - g) sigma_s must be at least 1e-30 /mm (1e-31)");
  EXPECT_EQ(with([](BssrdfConfig& c) { c.sigma_a = 0, c.sigma_s = 1e-30, c.g = 0; }), "");
  EXPECT_EQ(with([](BssrdfConfig& c) { c.g = 1; }), "g is outside (-1, 1) (1)");
  EXPECT_EQ(with([](BssrdfConfig& c) { c.g = -1.5; }), "g is outside (-1, 1) (-1.5)");
  EXPECT_EQ(with([](BssrdfConfig& c) { c.eta = 0; }), "eta is not positive (0)");
  EXPECT_EQ(with([](BssrdfConfig& c) { c.ni = dvec3(0, 0, 2); }), "ni is not a unit vector (length 2)");
  EXPECT_EQ(with([](BssrdfConfig& c) { c.no = dvec3(0); }), "no is not a unit vector (length 0)");
  EXPECT_EQ(with([](BssrdfConfig& c) { c.wi = dvec3(0, 0, 1.01); }), "wi is not a unit vector (length 1.01)");
  EXPECT_EQ(with([](BssrdfConfig& c) { c.xo.y = NAN; }), "xo_y is not finite (nan)");
  EXPECT_EQ(with([](BssrdfConfig& c) { c.eta = INFINITY; }), "eta is not finite (inf)");
  // Within 1e-3 of unit length is accepted.
  EXPECT_EQ(with([](BssrdfConfig& c) { c.ni = dvec3(0, 0, 1.0009); }), "");
  BssrdfOptions noPanels;
  noPanels.pbdPanelsPerEfold = 0;
  EXPECT_EQ(errorOf([&] { evaluateBssrdf<double>(BssrdfModel::PhotonBeamDiffusion, ok, noPanels); }),
            "pbdPanelsPerEfold must be at least 1 (0)");
}

// --- Fresnel -----------------------------------------------------------------------------------

TEST(BssrdfFresnel, NormalIncidenceMatchesTheClosedForm) {
  for (double eta : {0.5, 0.75, 1.0, 1.33, 1.5, 2.5}) {
    const double r0 = (eta - 1) / (eta + 1);
    EXPECT_NEAR(fresnelTransmittance(1.0, eta), 1.0 - r0 * r0, 1e-15) << eta;
    EXPECT_NEAR(fresnelReflectance(1.0, eta), r0 * r0, 1e-15) << eta;
  }
  EXPECT_NEAR(fresnelReflectance(0.3, 1.0), 0.0, 1e-15);  // index-matched: no reflection at any angle
  EXPECT_EQ(fresnelReflectance(0.0, 1.5), 1.0);  // grazing
}

TEST(BssrdfFresnel, NoTransmittanceBeyondTheCriticalAngle) {
  for (double eta : {0.9, 1.0 / 1.33, 1.0 / 1.5, 0.5}) {
    const double cosCritical = std::sqrt(1.0 - eta * eta);
    EXPECT_EQ(fresnelTransmittance(cosCritical * 0.999, eta), 0.0) << eta;
    EXPECT_EQ(fresnelTransmittance(0.0, eta), 0.0) << eta;
    EXPECT_GT(fresnelTransmittance(cosCritical * 1.001, eta), 0.0) << eta;
  }
}

TEST(BssrdfFresnel, TransmittanceIsReciprocalBetweenTheTwoSides) {
  // T12 at θ_i equals T21 at the refracted θ_t (Stokes relations), for light from either side
  // as long as a transmitted ray exists; at normal incidence T(η) = T(1/η).
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 1000; ++i) {
    const double eta = 0.4 + 2.0 * u(rng);
    const double cosI = u(rng);
    const double sin2T = (1.0 - cosI * cosI) / (eta * eta);
    if (sin2T >= 1.0) continue;
    const double cosT = std::sqrt(1.0 - sin2T);
    EXPECT_NEAR(fresnelTransmittance(cosI, eta), fresnelTransmittance(cosT, 1.0 / eta), 1e-11) << eta << " " << cosI;
  }
  for (double eta : {0.6, 1.2, 1.5, 2.0})
    EXPECT_NEAR(fresnelTransmittance(1.0, eta), fresnelTransmittance(1.0, 1.0 / eta), 1e-15);
}

TEST(BssrdfFresnel, RefractedDirectionObeysSnellsLaw) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 1000; ++i) {
    const dvec3 n = randomUnit(rng);
    dvec3 w = randomUnit(rng);
    if (glm::dot(w, n) < 0) w = -w;
    const double eta = 0.5 + 1.5 * u(rng);
    const dvec3 t = sh::refractedDirection(w, n, eta);
    EXPECT_NEAR(glm::length(t), 1.0, 1e-12);
    EXPECT_LE(glm::dot(t, n), 1e-12);  // into the medium
    const double sinI = glm::length(glm::cross(w, n)), sinT = glm::length(glm::cross(t, n));
    if (sinI / eta < 1.0) {
      EXPECT_NEAR(sinI, eta * sinT, 1e-12);
      EXPECT_NEAR(glm::dot(glm::cross(n, w), glm::cross(n, -t)), sinI * sinT, 1e-12);  // same plane, same side
    } else {
      EXPECT_NEAR(glm::dot(t, n), 0.0, 1e-12);  // total internal reflection: grazing
    }
  }
  EXPECT_NEAR(glm::length(sh::refractedDirection(dvec3(0, 0, 1), dvec3(0, 0, 1), 1.3) - dvec3(0, 0, -1)), 0.0, 1e-15);
}

// --- C_φ and C_E (appendix A) -------------------------------------------------------------------

/// The fits exactly as appendix A prints them (the shared code evaluates them re-expanded about η = 1).
double printed2C1(double e) {
  if (e < 1) return 0.919317 - 3.4793 * e + 6.75335 * e * e - 7.80989 * std::pow(e, 3) + 4.98554 * std::pow(e, 4) -
                    1.36881 * std::pow(e, 5);
  return -9.23372 + 22.2272 * e - 20.9292 * e * e + 10.2291 * std::pow(e, 3) - 2.54396 * std::pow(e, 4) +
         0.254913 * std::pow(e, 5);
}
double printed3C2(double e) {
  if (e < 1) return 0.828421 - 2.62051 * e + 3.36231 * e * e - 1.95284 * std::pow(e, 3) + 0.236494 * std::pow(e, 4) +
                    0.145787 * std::pow(e, 5);
  return -1641.1 + 135.926 / std::pow(e, 3) - 656.175 / (e * e) + 1376.53 / e + 1213.67 * e - 568.556 * e * e +
         164.798 * std::pow(e, 3) - 27.0181 * std::pow(e, 4) + 1.91826 * std::pow(e, 5);
}

TEST(BssrdfFresnelIntegrals, ReExpandedFitsEqualThePrintedOnes) {
  for (int i = 0; i <= 420; ++i) {
    const double eta = 0.4 + 2.1 * i / 420.0;
    EXPECT_NEAR(sh::fresnelMoment2C1(eta), printed2C1(eta), 1e-11) << eta;
    EXPECT_NEAR(sh::fresnelMoment3C2(eta), printed3C2(eta), 1e-10) << eta;
    EXPECT_NEAR(cPhiPolynomial(eta), 0.25 * (1 - printed2C1(eta)), 1e-11) << eta;
    EXPECT_NEAR(cEPolynomial(eta), 0.5 * (1 - printed3C2(eta)), 1e-10) << eta;
  }
  // Outside [0.4, 2.5] the fits are held at the ends (C_φ would turn negative near η = 3).
  EXPECT_EQ(cPhiPolynomial(4.0), cPhiPolynomial(2.5));
  EXPECT_EQ(cEPolynomial(0.1), cEPolynomial(0.4));
  EXPECT_GT(cPhiPolynomial(2.5), 0.0);
}

TEST(BssrdfFresnelIntegrals, IntegralsAreExactAtIndexMatchAndAgreeWithASecondMethod) {
  EXPECT_NEAR(cPhiIntegrated(1.0), 0.25, 1e-13);
  EXPECT_NEAR(cEIntegrated(1.0), 0.5, 1e-13);
  // Second method: integrate over the cosine ν outside the medium instead (for η > 1 the
  // transmitted cone maps onto the whole outer hemisphere, μ dμ = ν dν/η²; reciprocity
  // T_inside(μ) = T_outside(ν)); or over μ directly for η ≤ 1 with a plain composite rule.
  for (double eta : {0.5, 0.8, 1.05, 1.3, 1.5, 2.0}) {
    double phi = 0, e = 0;
    if (eta > 1) {
      phi = 0.5 / (eta * eta) *
            integrate([&](double nu) { return fresnelTransmittance(nu, eta) * nu; }, 0, 1, 1e-15);
      e = 1.5 / (eta * eta) * integrate(
                                  [&](double nu) {
                                    const double mu = std::sqrt(1 - (1 - nu * nu) / (eta * eta));
                                    return fresnelTransmittance(nu, eta) * nu * mu;
                                  },
                                  0, 1, 1e-15);
    } else {
      phi = 0.5 * integrate([&](double mu) { return fresnelTransmittance(mu, 1 / eta) * mu; }, 0, 1, 1e-15);
      e = 1.5 * integrate([&](double mu) { return fresnelTransmittance(mu, 1 / eta) * mu * mu; }, 0, 1, 1e-15);
    }
    EXPECT_NEAR(cPhiIntegrated(eta), phi, 1e-11) << eta;
    EXPECT_NEAR(cEIntegrated(eta), e, 1e-11) << eta;
  }
}

TEST(BssrdfFresnelIntegrals, PolynomialFitsAgreeWithTheIntegralsOnHalfToTwo) {
  // d'Eon and Irving do not state the fits' accuracy; measured here on a grid of 3001 points of
  // [0.5, 2]: |ΔC_φ| < 4.9e-5 and |ΔC_E| < 1.6e-4 on [0.5, 1) (largest just below 1), < 1.07e-3
  // and < 3.32e-3 on (1, 2], and at the junction η = 1 of the two pieces, where the η ≥ 1 pieces
  // give 2C_1 = 0.004333 and 3C_2 = −0.00684 instead of 0, |ΔC_φ| = 1.083e-3, |ΔC_E| = 3.42e-3.
  // The bounds asserted are these maxima, rounded up: the fits' own accuracy, not a tolerance of
  // the integration (which is exact to 1e-11, above).
  double worstBelow[2] = {0, 0}, worst[2] = {0, 0};
  for (int i = 0; i <= 3000; ++i) {
    const double eta = 0.5 + 1.5 * i / 3000.0;
    const double dPhi = std::abs(cPhiPolynomial(eta) - cPhiIntegrated(eta));
    const double dE = std::abs(cEPolynomial(eta) - cEIntegrated(eta));
    double* w = eta < 1 ? worstBelow : worst;
    w[0] = std::max(w[0], dPhi);
    w[1] = std::max(w[1], dE);
  }
  EXPECT_LT(worstBelow[0], 5e-5);
  EXPECT_LT(worstBelow[1], 1.6e-4);
  EXPECT_LT(worst[0], 1.1e-3);
  EXPECT_LT(worst[1], 3.5e-3);
  EXPECT_NEAR(cPhiPolynomial(1.0), 0.25 * (1 - 0.004333), 1e-15);
  EXPECT_NEAR(cEPolynomial(1.0), 0.5 * (1 + 0.00684), 1e-15);
  std::printf("[ fits    ] max |fit - integral| on [0.5, 1): C_phi %.3g, C_E %.3g; on [1, 2]: C_phi %.3g, C_E %.3g\n",
              worstBelow[0], worstBelow[1], worst[0], worst[1]);
}

// --- Derived coefficients ------------------------------------------------------------------------

TEST(BssrdfCoefficientsTest, DerivedQuantitiesFollowTheirDefinitions) {
  const double sa = 0.0021, ss = 2.19, g = 0.3, eta = 1.5;  // marble red, with some anisotropy
  const BssrdfCoefficients k = bssrdfCoefficients(sa, ss, g, eta);
  const double ssp = ss * (1 - g), stp = sa + ssp, D = 1 / (3 * stp);
  EXPECT_DOUBLE_EQ(k.sigma_t, sa + ss);
  EXPECT_DOUBLE_EQ(k.sigma_s_reduced, ssp);
  EXPECT_DOUBLE_EQ(k.sigma_t_reduced, stp);
  EXPECT_DOUBLE_EQ(k.albedo_reduced, ssp / stp);
  EXPECT_DOUBLE_EQ(k.D, D);
  EXPECT_NEAR(k.sigma_tr, std::sqrt(3 * sa * stp), 1e-15);
  EXPECT_NEAR(k.d_e, 2.131 * D / std::sqrt(ssp / stp), 1e-15);
  EXPECT_NEAR(k.A, (1 - k.c_e) / (2 * k.c_phi), 1e-15);
  EXPECT_NEAR(k.A, (1 + printed3C2(eta)) / (1 - printed2C1(eta)), 1e-10);  // Habel's form of Eq. 22
  EXPECT_NEAR(k.c_phi_inv, cPhiPolynomial(1 / eta), 1e-15);
  const double fdr = -1.440 / (eta * eta) + 0.710 / eta + 0.668 + 0.0636 * eta;
  EXPECT_NEAR(k.A_jensen, (1 + fdr) / (1 - fdr), 1e-14);
  EXPECT_NEAR(k.z_v, 1 / stp + 4 * k.A_jensen * D, 1e-14);
  EXPECT_NEAR(k.D_grosjean, (2 * sa + ssp) / (3 * stp * stp), 1e-15);
  EXPECT_NEAR(k.pbd_min_distance, 0.25 / (2 * sa + ss), 1e-16);
  // Without scattering d_e stays finite (α' is bounded below by 1e-12).
  EXPECT_TRUE(std::isfinite(bssrdfCoefficients(0.1, 0.0, 0.0, 1.3).d_e));
}

// --- Standard dipole ------------------------------------------------------------------------------

TEST(BssrdfStandardDipole, TotalDiffuseReflectanceMatchesJensensClosedForm) {
  // ∫₀^∞ R_d(r) 2πr dr = (α'/2)(1 + e^{−(4/3)A√(3(1−α'))}) e^{−√(3(1−α'))} (Jensen et al. 2001).
  struct Case {
    double sa, ss, g, eta;
  };
  for (const Case c : {Case{0.0021, 2.19, 0.0, 1.5}, Case{0.032, 0.74, 0.0, 1.3}, Case{0.1, 1.0, 0.5, 1.0},
                       Case{1.0, 1.0, 0.0, 1.33}, Case{0.01, 20.0, 0.9, 2.0}}) {
    const BssrdfCoefficients k = bssrdfCoefficients(c.sa, c.ss, c.g, c.eta);
    const double a = k.albedo_reduced, s = std::sqrt(3 * (1 - a));
    const double closed = 0.5 * a * (1 + std::exp(-4.0 / 3.0 * k.A_jensen * s)) * std::exp(-s);
    const sh::BssrdfCoefficients ks = sh::bssrdfCoefficients(c.sa, c.ss, c.g, c.eta);
    const auto f = [&](double r) { return sh::standardDipoleRd(r, ks).sd * 2 * kPi * r; };
    double total = 0, a0 = 0;  // geometric intervals out to where e^{−σ_tr r} < 1e-30
    for (double b = k.z_r; a0 < 70.0 / k.sigma_tr; b *= 2) {
      total += integrate(f, a0, b, 1e-15);
      a0 = b;
    }
    EXPECT_NEAR(total, closed, 1e-6 * closed) << c.sa << " " << c.ss;
    // And S_d = R_d/π through the public face.
    const BssrdfConfig cfg = planarConfig(0.7, 0.2, 40, c.sa, c.ss, c.g, c.eta);
    EXPECT_NEAR(sd(BssrdfModel::Standard, cfg), sh::standardDipoleRd(std::hypot(0.7, 0.2), ks).sd / kPi, 1e-16);
  }
}

// --- Directional dipole ---------------------------------------------------------------------------

TEST(BssrdfDirectionalDipole, Eq19IsTheGradientOfEq9) {
  std::mt19937_64 rng(19);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    const sh::BssrdfCoefficients k = sh::bssrdfCoefficients(0.01 + u(rng), 0.2 + 3 * u(rng), 0.9 * u(rng), 1.3);
    const dvec3 w = randomUnit(rng);
    const dvec3 x = (0.05 + 3 * u(rng)) * randomUnit(rng);
    const dvec3 grad = sh::rayFluenceGradient(x, w, glm::length(x), k);
    const double h = 1e-5 * glm::length(x);
    dvec3 fd;
    for (int a = 0; a < 3; ++a) {
      dvec3 e(0.0);
      e[a] = h;
      fd[a] = (sh::rayFluence(x + e, w, glm::length(x + e), k) - sh::rayFluence(x - e, w, glm::length(x - e), k)) /
              (2 * h);
    }
    EXPECT_LT(glm::length(fd - grad), 1e-7 * glm::length(grad) + 1e-12) << i;
  }
}

/// Eq. 20 as the radiosity-maps paper's appendix A transcribes it (C_E bracket closed early).
double transcribedEq20(const dvec3& x, const dvec3& w, double r, const dvec3& no, const sh::BssrdfCoefficients& k) {
  const double sr = k.sigmaTr * r, op = 1 + sr;
  const double bracket = k.cPhi * (r * r / k.D + 3 * op * glm::dot(x, w)) - k.cE * (3 * k.D * op * glm::dot(w, no)) -
                         (op + 3 * k.D * (3 * op + sr * sr) / (r * r) * glm::dot(x, w)) * glm::dot(x, no);
  return std::exp(-sr) / (r * r * r) * bracket / (16 * kPi * kPi * k.cPhiInv);
}

TEST(BssrdfDirectionalDipole, Eq20IsEq18WithEqs9And19) {
  // S'_d = (C_φ φ − C_E D n_o·∇φ)/(4π C_φ(1/η)) (Eqs. 16, 18), for r = |x| and for the corrected
  // distance d_r ≠ |x| that the model substitutes (§3.3.3); the transcription that closes the C_E
  // bracket before the x·n_o term is not this whenever x·n_o ≠ 0.
  std::mt19937_64 rng(20);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int transcriptionDiffers = 0;
  for (int i = 0; i < 500; ++i) {
    const sh::BssrdfCoefficients k =
        sh::bssrdfCoefficients(0.001 + u(rng), 0.1 + 3 * u(rng), 0.95 * u(rng), 0.7 + 1.1 * u(rng));
    const dvec3 w = randomUnit(rng), no = randomUnit(rng);
    const dvec3 x = (0.01 + 3 * u(rng)) * randomUnit(rng);
    for (double r : {glm::length(x), glm::length(x) * (1 + u(rng))}) {
      const double phi = sh::rayFluence(x, w, r, k);
      const dvec3 gradient = sh::rayFluenceGradient(x, w, r, k);
      const double eq18 = (k.cPhi * phi - k.cE * k.D * glm::dot(no, gradient)) / (4 * kPi * k.cPhiInv);
      const double eq20 = sh::raySourceBssrdf(x, w, r, no, k);
      EXPECT_NEAR(eq20, eq18, 1e-12 * (std::abs(eq18) + 1e-300)) << i;
      if (std::abs(transcribedEq20(x, w, r, no, k) - eq18) > 1e-6 * std::abs(eq18)) ++transcriptionDiffers;
    }
  }
  EXPECT_GT(transcriptionDiffers, 900);
}

TEST(BssrdfDirectionalDipole, MirrorSymmetricAboutThePlaneOfIncidence) {
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 500; ++i) {
    BssrdfConfig c{randomUnit(rng), randomUnit(rng), randomUnit(rng), dvec3(0), randomUnit(rng),
                   0.001 + u(rng), 0.1 + 3 * u(rng), 0.9 * u(rng), 0.8 + 0.8 * u(rng)};
    if (glm::dot(c.wi, c.ni) < 0) c.wi = -c.wi;
    c.xo = c.xi + (0.05 + 3 * u(rng)) * randomUnit(rng);
    // Mirror x_o and n_o in the plane of incidence (through x_i, spanned by n_i and w_i).
    const dvec3 p = glm::normalize(glm::cross(c.ni, c.wi));
    BssrdfConfig m = c;
    m.xo = c.xi + mirror(c.xo - c.xi, p);
    m.no = mirror(c.no, p);
    for (BssrdfModel model : {BssrdfModel::Directional, BssrdfModel::PhotonBeamDiffusion}) {
      const double a = sd(model, c), b = sd(model, m);
      EXPECT_NEAR(a, b, 1e-9 * bssrdfMagnitude(model, c)) << bssrdfModelName(model) << " " << i;
    }
  }
}

TEST(BssrdfDirectionalDipole, RadiallySymmetricAtNormalIncidence) {
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    const double r = 0.02 + 4 * u(rng), eta = 0.8 + 0.8 * u(rng);
    BssrdfConfig c = planarConfig(r, 0, 0, 0.001 + u(rng), 0.1 + 3 * u(rng), 0.9 * u(rng), eta);
    const double ref = sd(BssrdfModel::Directional, c), refPbd = sd(BssrdfModel::PhotonBeamDiffusion, c);
    for (int j = 1; j < 6; ++j) {
      const double phi = 2 * kPi * u(rng);
      c.xo = dvec3(r * std::cos(phi), r * std::sin(phi), 0);
      EXPECT_NEAR(sd(BssrdfModel::Directional, c), ref, 1e-11 * std::abs(ref) + 1e-300) << i;
      EXPECT_NEAR(sd(BssrdfModel::PhotonBeamDiffusion, c), refPbd, 1e-9 * std::abs(refPbd) + 1e-300) << i;
    }
  }
}

TEST(BssrdfDirectionalDipole, ProfileLeansForwardAtObliqueIncidence) {
  // Figs. 5–6: light incident at 60° from the −x side travels toward +x inside; S_d at +x exceeds
  // S_d at −x the same distance away (σ_s = 1 cm⁻¹, σ_a = 0.01 cm⁻¹, η = 1). The standard dipole
  // cannot tell the two apart.
  for (double x : {1.0, 3.0, 10.0}) {
    const double forward = sd(BssrdfModel::Directional, planarConfig(x, 0, 60, 0.001, 0.1, 0, 1));
    const double backward = sd(BssrdfModel::Directional, planarConfig(-x, 0, 60, 0.001, 0.1, 0, 1));
    EXPECT_GT(forward, backward) << x;
    EXPECT_EQ(sd(BssrdfModel::Standard, planarConfig(x, 0, 60, 0.001, 0.1, 0, 1)),
              sd(BssrdfModel::Standard, planarConfig(-x, 0, 60, 0.001, 0.1, 0, 1)));
  }
}

TEST(BssrdfDirectionalDipole, ModifiedTangentPlaneBehavesAsEq23Says) {
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 300; ++i) {
    const sh::BssrdfCoefficients k = sh::bssrdfCoefficients(0.001 + u(rng), 0.1 + 3 * u(rng), 0.9 * u(rng), 1.3);
    const dvec3 xi = randomUnit(rng), ni = randomUnit(rng);
    dvec3 wi = randomUnit(rng);
    if (glm::dot(wi, ni) < 0) wi = -wi;
    // x_o in the tangent plane of x_i, n_o anything: n_i* = n_i, x_v = x_i + 2A d_e n_i.
    const dvec3 tangent = glm::normalize(glm::cross(ni, randomUnit(rng)));
    const dvec3 xo = xi + (0.1 + 2 * u(rng)) * tangent;
    const sh::DirectionalDipoleGeometry g = sh::directionalDipoleGeometry(xi, ni, wi, xo, randomUnit(rng), k);
    EXPECT_LT(glm::length(g.niStar - ni), 1e-12);
    EXPECT_LT(glm::length(g.xv - 2 * k.A * k.de * ni), 1e-12 * k.de);
    // x_o off the tangent plane: n_i* is the unit vector ⊥ x_o − x_i in the plane of n_i and
    // x_o − x_i, on n_i's side; n_o does not move the virtual source.
    const dvec3 xo2 = xo + (u(rng) - 0.5) * 2 * ni;
    const dvec3 x = xo2 - xi;
    const sh::DirectionalDipoleGeometry g2 = sh::directionalDipoleGeometry(xi, ni, wi, xo2, randomUnit(rng), k);
    const sh::DirectionalDipoleGeometry g3 = sh::directionalDipoleGeometry(xi, ni, wi, xo2, randomUnit(rng), k);
    EXPECT_NEAR(glm::length(g2.niStar), 1.0, 1e-12);
    EXPECT_NEAR(glm::dot(g2.niStar, x), 0.0, 1e-12 * glm::length(x));
    EXPECT_NEAR(glm::dot(g2.niStar, glm::cross(ni, x)), 0.0, 1e-12 * glm::length(x));
    EXPECT_GT(glm::dot(g2.niStar, ni), 0.0);
    EXPECT_LT(glm::length(g2.niStar - g3.niStar) + glm::length(g2.xv - g3.xv) + glm::length(g2.wv - g3.wv), 1e-15);
    EXPECT_NEAR(glm::dot(g2.wv, g2.niStar), -glm::dot(g2.w12, g2.niStar), 1e-12);  // ω_v mirrors ω12
    // At η = 1 the refracted ray does not depend on n_i (as long as w_i is on the outer side of
    // both normals), so the whole model sees the configuration as planar with normal n_i*:
    // S_d(n_i) = S_d(n_i*).
    if (glm::dot(wi, g2.niStar) <= 0) continue;
    const dvec3 no = randomUnit(rng);
    BssrdfConfig c{xi, ni, wi, xo2, no, k.sigmaA, k.sigmaS, k.g, 1.0};
    BssrdfConfig planar = c;
    planar.ni = g2.niStar;
    EXPECT_NEAR(sd(BssrdfModel::Directional, c), sd(BssrdfModel::Directional, planar),
                1e-10 * bssrdfMagnitude(BssrdfModel::Directional, c));
  }
  // x_o − x_i ∥ n_i (Eq. 23 undefined) and x_o = x_i: n_i.
  const sh::BssrdfCoefficients k = sh::bssrdfCoefficients(0.01, 1, 0, 1.3);
  const dvec3 n(0, 0, 1);
  EXPECT_EQ(sh::directionalDipoleGeometry(dvec3(0), n, n, dvec3(0, 0, 0.5), n, k).niStar, n);
  EXPECT_EQ(sh::directionalDipoleGeometry(dvec3(0), n, n, dvec3(0, 0, -0.5), n, k).niStar, n);
  EXPECT_EQ(sh::directionalDipoleGeometry(dvec3(0), n, n, dvec3(0), n, k).niStar, n);
}

TEST(BssrdfDirectionalDipole, RealSourceDistanceFollowsEqs24And25) {
  const sh::BssrdfCoefficients k = sh::bssrdfCoefficients(0.01, 1.0, 0.0, 1.3);
  // Normal incidence, x_o = x_i: d_r = D μ0 with μ0 = 1 (cos β = 0).
  EXPECT_NEAR(sh::directionalDipoleGeometry(dvec3(0), dvec3(0, 0, 1), dvec3(0, 0, 1), dvec3(0), dvec3(0, 0, 1), k).dr,
              k.D, 1e-15);
  // Backlit (n_o along the refracted ray): d_r² = r² + 1/(3σ_t)².
  const auto g = sh::directionalDipoleGeometry(dvec3(0), dvec3(0, 0, 1), dvec3(0, 0, 1), dvec3(0, 0, -2),
                                               dvec3(0, 0, -1), k);
  EXPECT_LT(g.mu0, 0.0);
  EXPECT_NEAR(g.dr, std::sqrt(4 + 1 / (9 * k.sigmaT * k.sigmaT)), 1e-14);
  // Frontlit, oblique: r² + Dμ0(Dμ0 − 2 d_e cos β), cos β = −√((r² − (x·ω12)²)/(r² + d_e²)).
  const BssrdfConfig c = planarConfig(0.8, 0.3, 50, 0.01, 1.0, 0.0, 1.3);
  const auto g2 = sh::directionalDipoleGeometry(c.xi, c.ni, c.wi, c.xo, c.no, k);
  const dvec3 x = c.xo - c.xi;
  const double r2 = glm::dot(x, x), xw = glm::dot(x, g2.w12);
  const double cosBeta = -std::sqrt((r2 - xw * xw) / (r2 + k.de * k.de));
  EXPECT_NEAR(g2.dr * g2.dr, r2 + k.D * g2.mu0 * (k.D * g2.mu0 - 2 * k.de * cosBeta), 1e-14);
}

// --- Reciprocal variant ---------------------------------------------------------------------------

TEST(BssrdfReciprocal, EqualsTheAverageWithSwappedArguments) {
  std::mt19937_64 rng(37);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    BssrdfConfig c{randomUnit(rng), randomUnit(rng), randomUnit(rng), dvec3(0), randomUnit(rng),
                   0.001 + u(rng), 0.1 + 3 * u(rng), 0.9 * u(rng), 0.8 + 0.8 * u(rng)};
    if (glm::dot(c.wi, c.ni) < 0) c.wi = -c.wi;
    c.xo = c.xi + (0.05 + 3 * u(rng)) * randomUnit(rng);
    const BssrdfConfig swapped{c.xo, c.no, c.no, c.xi, c.ni, c.sigma_a, c.sigma_s, c.g, c.eta};
    for (BssrdfModel m : {BssrdfModel::Standard, BssrdfModel::Directional, BssrdfModel::PhotonBeamDiffusion}) {
      const double rec = evaluateBssrdf<double>(m, c, true).sd;
      EXPECT_NEAR(rec, 0.5 * (sd(m, c) + sd(m, swapped)), 1e-14 * bssrdfMagnitude(m, c, {true})) << i;
      EXPECT_EQ(evaluateBssrdf<double>(m, c, true).sdClamped, std::max(rec, 0.0));
    }
    // With w_i = n_i the variant is symmetric under the swap.
    BssrdfConfig n = c;
    n.wi = n.ni;
    const BssrdfConfig nSwapped{n.xo, n.no, n.no, n.xi, n.ni, n.sigma_a, n.sigma_s, n.g, n.eta};
    const double a = evaluateBssrdf<double>(BssrdfModel::Directional, n, true).sd;
    EXPECT_NEAR(a, evaluateBssrdf<double>(BssrdfModel::Directional, nSwapped, true).sd,
                1e-13 * bssrdfMagnitude(BssrdfModel::Directional, n, {true}));
  }
}

// --- Photon beam diffusion -----------------------------------------------------------------------

/// Independent implementation of PBD on a planar surface z = 0 (n_i = n_o = z), written from
/// Habel et al.'s formulas (PBD Eqs. 5, 10, 12; [cid] Eqs. 16, 23, 26, 27) with the planar identity
/// d_v² = d_r² + 4z_b z_r + 4z_b², the clamp of d_r and d_v in denominators, the directional
/// dipole's normalisation 1/(4π C_φ(1/η)), and adaptive Gauss–Kronrod along the beam.
double pbdPlanarReference(const BssrdfConfig& c) {
  const double ssp = c.sigma_s * (1 - c.g), stp = c.sigma_a + ssp, alpha = ssp / stp;
  const double Dg = (2 * c.sigma_a + ssp) / (3 * stp * stp), str = std::sqrt(c.sigma_a / Dg);
  const double cPhi = 0.25 * (1 - printed2C1(c.eta)), cE = 0.5 * (1 - printed3C2(c.eta));
  const double A = (1 + printed3C2(c.eta)) / (1 - printed2C1(c.eta)), zb = 2 * A * Dg;
  const double clampD = 0.25 / (2 * c.sigma_a + c.sigma_s);
  // Refraction in the xz-plane: incidence from direction w_i, beam (sin θ_t along −w_i's
  // tangential part, −cos θ_t).
  const double cosI = c.wi.z, sinI = std::sqrt(1 - cosI * cosI), sinT = sinI / c.eta,
               cosT = std::sqrt(1 - sinT * sinT);
  const dvec3 tangential = sinI > 0 ? -dvec3(c.wi.x, c.wi.y, 0) / sinI : dvec3(0);
  const dvec3 beam = sinT * tangential + dvec3(0, 0, -cosT);
  const auto integrand = [&](double t) {
    const dvec3 xr = c.xi + t * beam;
    const double zr = t * cosT;
    const double dr = glm::length(c.xo - xr);
    const double dv = std::sqrt(dr * dr + 4 * zb * zr + 4 * zb * zb);
    const double drc = std::max(dr, clampD), dvc = std::max(dv, clampD);
    const double Q = alpha * stp * std::exp(-stp * t);
    const double kappa = 1 - std::exp(-2 * stp * (dr + t));
    const double Rphi = alpha / (4 * kPi) / Dg * (std::exp(-str * dr) / drc - std::exp(-str * dv) / dvc);
    const double RE = alpha / (4 * kPi) *
                      (zr * (1 + str * dr) * std::exp(-str * dr) / (drc * drc * drc) +
                       (zr + 2 * zb) * (1 + str * dv) * std::exp(-str * dv) / (dvc * dvc * dvc));
    return Q * kappa * (cPhi * Rphi + cE * RE);
  };
  // Break at the closest approach and the clamp kinks, then geometric intervals.
  const dvec3 x = c.xo - c.xi;
  const double ts = glm::dot(x, beam), h = glm::length(x - ts * beam);
  std::vector<double> cuts = {0.0};
  for (double t : {ts, h < clampD ? ts - std::sqrt(clampD * clampD - h * h) : -1.0,
                   h < clampD ? ts + std::sqrt(clampD * clampD - h * h) : -1.0})
    if (t > 0) cuts.push_back(t);
  std::sort(cuts.begin(), cuts.end());
  double total = 0;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) total += integrate(integrand, cuts[i], cuts[i + 1], 1e-17);
  for (double a = cuts.back(), b = a + 1 / stp; a < cuts.back() + 60 / stp; a = b, b += 2 / stp)
    total += integrate(integrand, a, b, 1e-17);
  const double cPhiInv = 0.25 * (1 - printed2C1(1 / c.eta));
  return total / (4 * kPi * cPhiInv);
}

TEST(BssrdfPhotonBeamDiffusion, AgreesWithAnIndependentIntegrationOnAPlane) {
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double worst = 0;
  for (int i = 0; i < 300; ++i) {
    const double sa = std::pow(10.0, -3 + 3 * u(rng)), ss = std::pow(10.0, -1 + 2 * u(rng));
    const double g = 0.95 * u(rng), eta = 1.0 + 0.6 * u(rng);
    const double r = i % 10 == 0 ? 0.0 : std::pow(10.0, -3 + 4 * u(rng)), phi = 2 * kPi * u(rng);
    const BssrdfConfig c = planarConfig(r * std::cos(phi), r * std::sin(phi), 85 * u(rng), sa, ss, g, eta);
    const double ref = pbdPlanarReference(c);
    const double got = sd(BssrdfModel::PhotonBeamDiffusion, c);
    const double scale = bssrdfMagnitude(BssrdfModel::PhotonBeamDiffusion, c);
    worst = std::max(worst, std::abs(got - ref) / scale);
    EXPECT_NEAR(got, ref, 1e-6 * scale) << "case " << i << " r=" << r << " sa=" << sa << " ss=" << ss;
    EXPECT_GT(ref, 0.0);  // on a plane every term is positive: scale = S_d
  }
  std::printf("[ pbd     ] largest |default - reference| / scale on the plane: %.3g\n", worst);
}

TEST(BssrdfPhotonBeamDiffusion, DefaultQuadratureHasConvergedAnywhere) {
  // Arbitrary (curved-surface) configurations, x_o on or off the beams: the default against 8
  // panels per e-fold. The error is measured against the integral of |M| (the scale), which the
  // value itself reaches where the real and virtual beams do not cancel.
  std::mt19937_64 rng(43);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  BssrdfOptions fine;
  fine.pbdPanelsPerEfold = 8;
  double worst = 0;
  for (int i = 0; i < 2000; ++i) {
    BssrdfConfig c{dvec3(0), randomUnit(rng), randomUnit(rng), dvec3(0), randomUnit(rng),
                   std::pow(10.0, -3 + 3 * u(rng)), std::pow(10.0, -1 + 2 * u(rng)), 0.99 * (2 * u(rng) - 1),
                   0.6 + 1.2 * u(rng)};
    if (glm::dot(c.wi, c.ni) < 0) c.wi = -c.wi;
    const double len = std::pow(10.0, -4 + 5 * u(rng));
    c.xo = i % 7 == 0 ? len * sh::refractedDirection(c.wi, c.ni, c.eta) : len * randomUnit(rng);  // some on the beam
    const double a = sd(BssrdfModel::PhotonBeamDiffusion, c);
    const double b = evaluateBssrdf<double>(BssrdfModel::PhotonBeamDiffusion, c, fine).sd;
    const double scale = bssrdfMagnitude(BssrdfModel::PhotonBeamDiffusion, c, fine);
    if (scale == 0) continue;
    worst = std::max(worst, std::abs(a - b) / scale);
    EXPECT_NEAR(a, b, 1e-6 * scale) << i;
  }
  std::printf("[ pbd     ] largest |default - 8 panels/e-fold| / scale: %.3g\n", worst);
}

TEST(BssrdfPhotonBeamDiffusion, ClampKeepsTheBeamEntryFinite) {
  // At x_o = x_i the unclamped integral diverges (z_r/d_r³ ~ 1/t near t = 0).
  const BssrdfConfig c = planarConfig(0, 0, 0, 0.01, 1.0, 0.0, 1.3);
  const double v = sd(BssrdfModel::PhotonBeamDiffusion, c);
  EXPECT_TRUE(std::isfinite(v));
  EXPECT_GT(v, 0.0);
  EXPECT_NEAR(v, pbdPlanarReference(c), 1e-6 * v);
}

TEST(BssrdfModels, FloatAgreesWithDoubleOnTypicalConfigurations) {
  std::mt19937_64 rng(47);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 500; ++i) {
    const double r = 0.05 + 5 * u(rng), phi = 2 * kPi * u(rng);
    const BssrdfConfig c = planarConfig(r * std::cos(phi), r * std::sin(phi), 80 * u(rng), 0.001 + 0.1 * u(rng),
                                        0.5 + 3 * u(rng), 0.9 * u(rng), 1.0 + 0.5 * u(rng));
    for (BssrdfModel m : {BssrdfModel::Standard, BssrdfModel::Directional, BssrdfModel::PhotonBeamDiffusion}) {
      const double d = sd(m, c), f = evaluateBssrdf<float>(m, c).sd;
      EXPECT_NEAR(f, d, 1e-4 * bssrdfMagnitude(m, c)) << bssrdfModelName(m) << " " << i;
    }
  }
}

}  // namespace
}  // namespace tallow::sss
