// SSLPV's shared SH arithmetic (shaders/peers/sslpv/sh.glsl, compiled as C++ by sss/peers/sslpv_math.h: the
// lines the GPU runs) and the propagation matrices, against numerical integration written here,
// closed forms and the matrix the paper prints (Børlum et al. 2011, §4).
#include "sss/peers/sslpv_math.h"

#include <gtest/gtest.h>

#include "sss/bssrdf/material.h"

#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include "support/dipole_totals.h"
#include "support/slab_recursion.h"

namespace tallow::sss {
namespace {

namespace sh = sslpv_glsl;
constexpr double kPi = 3.14159265358979323846;

/// The real SH basis written out here: (y00, y1−1, y10, y11) = (1/√(4π), √(3/4π)(y, z, x)).
glm::dvec4 basis(const glm::dvec3& w) {
  const double a = 0.5 / std::sqrt(kPi), b = std::sqrt(3.0 / (4.0 * kPi));
  return {a, b * w.y, b * w.z, b * w.x};
}

/// ∫ f(ω) g(ω) dω over the sphere (or the part where f ≠ 0) by the midpoint rule on a θ × φ grid of
/// 600 × 1200 cells: smooth integrands converge as O(h²) ≈ 10⁻⁵; the clamped ones have a kink
/// along a great circle, which costs about as much.
glm::dvec4 project(const std::function<double(const glm::dvec3&)>& f) {
  constexpr int nt = 600, np = 1200;
  glm::dvec4 sum(0.0);
  for (int i = 0; i < nt; ++i) {
    const double theta = (i + 0.5) * kPi / nt, st = std::sin(theta), ct = std::cos(theta);
    const double dOmega = st * (kPi / nt) * (2.0 * kPi / np);
    for (int j = 0; j < np; ++j) {
      const double phi = (j + 0.5) * 2.0 * kPi / np;
      const glm::dvec3 w(st * std::cos(phi), st * std::sin(phi), ct);
      const double v = f(w);
      if (v != 0.0) sum += v * dOmega * basis(w);
    }
  }
  return sum;
}

double integrate(const std::function<double(const glm::dvec3&)>& f) { return project(f)[0] * 2.0 * std::sqrt(kPi); }

glm::dvec3 randomDirection(std::mt19937& rng) {
  std::normal_distribution<double> n;
  return glm::normalize(glm::dvec3(n(rng), n(rng), n(rng)));
}

void expectNear4(const glm::dvec4& a, const glm::dvec4& b, double tol, const char* what) {
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(a[k], b[k], tol) << what << " coefficient " << k;
}

TEST(SslpvSh, BasisAndCosineLobeMatchNumericalProjection) {
  std::mt19937 rng(1);
  for (int t = 0; t < 3; ++t) {
    const glm::dvec3 a = randomDirection(rng);
    for (int k = 0; k < 4; ++k)
      EXPECT_NEAR(sh::sslpvBasis(glm::vec3(a))[k], basis(a)[k], 1e-6) << "basis " << k;
    // The clamped cosine lobe max(0, a·ω)/π: its projection and its unit flux. 2·10⁻⁵ covers the
    // quadrature (the kink along a·ω = 0) and float.
    const glm::dvec4 numeric = project([&](const glm::dvec3& w) { return std::max(0.0, glm::dot(a, w)) / kPi; });
    expectNear4(glm::dvec4(sh::sslpvCosineLobe(glm::vec3(a))), numeric, 2e-5, "cosine lobe");
    EXPECT_NEAR(sh::sslpvFlux(sh::sslpvCosineLobe(glm::vec3(a))), 1.0, 1e-6);
  }
}

TEST(SslpvSh, RotationToTheNormalFrameMatchesProjectionOnTheRotatedBasis) {
  // Eq. 6: c^(n) = R_SH(α, β, 0)⁻¹ c with tan α = n_y/n_x, cos β = n_z. The rotated frame, built
  // here from the Euler angles (R = R_z(α) R_y(β)): x' = R e_x, y' = R e_y, z' = R e_z = n; the
  // coefficients in it are ∫ I(ω) y_lm(ω') dω with ω' = (ω·x', ω·y', ω·z').
  std::mt19937 rng(2);
  for (int t = 0; t < 4; ++t) {
    const glm::dvec3 n = t == 0 ? glm::dvec3(0, 0, 1) : t == 1 ? glm::dvec3(0, 0, -1) : randomDirection(rng);
    const glm::dvec3 d = randomDirection(rng);
    // A smooth intensity with both bands: 0.3 + 0.8 max(0, d·ω)/π, projected numerically.
    const auto intensity = [&](const glm::dvec3& w) { return 0.3 + 0.8 * std::max(0.0, glm::dot(d, w)) / kPi; };
    const glm::dvec4 c = project(intensity);
    const double alpha = std::atan2(n.y, n.x), beta = std::acos(std::clamp(n.z, -1.0, 1.0));
    const glm::dvec3 xr(std::cos(alpha) * std::cos(beta), std::sin(alpha) * std::cos(beta), -std::sin(beta));
    const glm::dvec3 yr(-std::sin(alpha), std::cos(alpha), 0.0);
    const glm::dvec3 zr(std::cos(alpha) * std::sin(beta), std::sin(alpha) * std::sin(beta), std::cos(beta));
    ASSERT_NEAR(glm::length(zr - n), 0.0, 1e-12);
    glm::dvec4 expected(0.0);
    {
      constexpr int nt = 400, np = 800;
      for (int i = 0; i < nt; ++i) {
        const double theta = (i + 0.5) * kPi / nt, st = std::sin(theta), ct = std::cos(theta);
        for (int j = 0; j < np; ++j) {
          const double phi = (j + 0.5) * 2.0 * kPi / np;
          const glm::dvec3 w(st * std::cos(phi), st * std::sin(phi), ct);
          const glm::dvec3 local(glm::dot(w, xr), glm::dot(w, yr), glm::dot(w, zr));
          expected += intensity(w) * st * (kPi / nt) * (2.0 * kPi / np) * basis(local);
        }
      }
    }
    const glm::dvec4 rotated(sh::sslpvRotateToNormal(glm::vec4(c), glm::vec3(n)));
    expectNear4(rotated, expected, 5e-5, "rotated");
    // The paper's explicit third row.
    EXPECT_NEAR(rotated[2], std::sin(alpha) * std::sin(beta) * c[1] + std::cos(beta) * c[2] +
                                std::cos(alpha) * std::sin(beta) * c[3], 1e-6);
  }
}

TEST(SslpvSh, AreaLightRadianceIsTheCapFluxOverAPi) {
  // Eqs. 5 and 7: L_i = (1/(Aπ)) ∫_cap I dω for the truncated expansion I = Σ c_lm y_lm, the cap
  // about n of half-angle θ_c (cos θ_c = 0: the hemisphere; 2/3: one cube face's solid angle).
  std::mt19937 rng(3);
  const double area = 2.5e-5;  // m², a 5 mm cell
  for (const double capCos : {0.0, 2.0 / 3.0}) {
    for (int t = 0; t < 3; ++t) {
      const glm::dvec3 n = randomDirection(rng);
      const glm::dvec4 c(0.7, 0.2 * (t + 1), -0.3, 0.25);
      // The cap by the midpoint rule in its own polar coordinates about n (θ ≤ θ_c, 400 × 800):
      // the integrand is smooth there, so the error is ~10⁻⁶.
      const glm::dvec3 t1 = glm::normalize(glm::cross(n, std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
      const glm::dvec3 t2 = glm::cross(n, t1);
      const double thetaC = std::acos(capCos);
      double flux = 0.0;
      constexpr int nt = 400, np = 800;
      for (int i = 0; i < nt; ++i) {
        const double theta = (i + 0.5) * thetaC / nt;
        for (int j = 0; j < np; ++j) {
          const double phi = (j + 0.5) * 2.0 * kPi / np;
          const glm::dvec3 w = std::sin(theta) * (std::cos(phi) * t1 + std::sin(phi) * t2) + std::cos(theta) * n;
          flux += glm::dot(c, basis(w)) * std::sin(theta) * (thetaC / nt) * (2.0 * kPi / np);
        }
      }
      const glm::vec4 cn = sh::sslpvRotateToNormal(glm::vec4(c), glm::vec3(n));
      // 10⁻⁵ relative: the quadrature and float.
      EXPECT_NEAR(sh::sslpvAreaLightRadiance(cn, static_cast<float>(area), static_cast<float>(capCos)),
                  flux / (area * kPi), 1e-5 * std::abs(flux) / (area * kPi))
          << "cap cos " << capCos;
    }
  }
}

TEST(SslpvSh, ScatteringMultipliesBandsByHenyeyGreensteinMoments) {
  // Eq. 2 numerically, I_sc(ω) = (1 − σ'_s) I(ω) + σ'_s ∫ p(ω·ω') I(ω') dω', with the HG phase
  // function p(μ) = (1 − g²)/(4π (1 + g² − 2gμ)^{3/2}), for I = Σ c y: its projection is Eq. 3.
  const glm::dvec4 c(1.0, 0.4, -0.2, 0.3);
  for (const double g : {0.0, 0.5, -0.3, 0.9}) {
    const double sigmaPrime = 0.7;
    // ∫ p(ω·ω') y1m(ω') dω' = g y1m(ω) (addition theorem): check it for one ω by quadrature.
    const glm::dvec3 w = glm::normalize(glm::dvec3(0.3, -0.5, 0.8));
    const auto hg = [&](double mu) { return (1 - g * g) / (4 * kPi * std::pow(1 + g * g - 2 * g * mu, 1.5)); };
    const double scattered = integrate([&](const glm::dvec3& v) { return hg(glm::dot(w, v)) * glm::dot(c, basis(v)); });
    const double expected = (1 - sigmaPrime) * glm::dot(c, basis(w)) + sigmaPrime * scattered;
    const glm::vec4 sc = sh::sslpvScatter(glm::vec4(c), static_cast<float>(sigmaPrime), static_cast<float>(g));
    // g = 0.9 is peaked (width ~ 1 − g = 0.1 rad, ~20 θ cells): 2·10⁻⁴ absolute on values ~0.3.
    EXPECT_NEAR(sh::sslpvEvaluate(sc, glm::vec3(w)), expected, 2e-4) << "g " << g;
  }
}

TEST(SslpvSh, TexelSolidAnglesOfACubeSumToTheSphere) {
  // §3.1's Δω_p = 4α tan²(FOV/2) cos³θ_p/(N_x N_y) on a 90° cube face (α = 1) against the exact
  // solid angle of each texel, the rectangle [x0, x1] × [y0, y1] on the plane at distance 1:
  // Ω = F(x1, y1) − F(x0, y1) − F(x1, y0) + F(x0, y0), F(x, y) = atan(xy/√(1 + x² + y²)).
  constexpr int n = 64;
  const auto F = [](double x, double y) { return std::atan(x * y / std::sqrt(1 + x * x + y * y)); };
  double total = 0.0, worst = 0.0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double x0 = -1 + 2.0 * i / n, x1 = x0 + 2.0 / n, y0 = -1 + 2.0 * j / n, y1 = y0 + 2.0 / n;
      const double exact = F(x1, y1) - F(x0, y1) - F(x1, y0) + F(x0, y0);
      const double xc = 0.5 * (x0 + x1), yc = 0.5 * (y0 + y1);
      const double cosTheta = 1.0 / std::sqrt(1 + xc * xc + yc * yc);
      const double approx = sh::sslpvTexelSolidAngle(static_cast<float>(cosTheta), 1.0f, 1.0f, n, n);
      total += approx;
      worst = std::max(worst, std::abs(approx / exact - 1.0));
    }
  // The texel-centre approximation errs by O((2/N)²) relative: 1/N² ≈ 2.4·10⁻⁴ at N = 64.
  EXPECT_LT(worst, 1e-3);
  EXPECT_NEAR(6.0 * total, 4.0 * kPi, 4.0 * kPi * 1e-3);
}

// --- The grid's medium ------------------------------------------------------------------------------

TEST(SslpvMediumMapping, SurvivalGivesTheDiffusionDecayOnTheLattice) {
  // In a cell many transport mean free paths thick, σ'_s ≈ 1 and g ≈ 0 make the propagation a walk
  // over the six neighbours (each gets 1/6 of an isotropic cell's flux, §4: Σ'_f M_{f,d←s} has 1/6
  // in its first entry) that keeps a = exp(−σ_t ΔX) per step. Its steady state from a plane source
  // (the walk in 1D: 1/6 up, 1/6 down, 4/6 within the layer) must fall off as e^{−σ_tr x}: iterate
  // it here and compare the ratio of neighbouring layers far from the source.
  struct Case {
    double sigmaA, sigmaS, cellMm;
  };
  for (const Case& k : {Case{0.0021, 2.19, 3.0}, Case{0.0071, 3.0, 6.25}, Case{0.032, 0.74, 6.0}}) {
    const double a = sh::sslpvSurvival(static_cast<float>(k.sigmaA), static_cast<float>(k.sigmaS), 0.0f,
                                       static_cast<float>(k.cellMm));
    const double sigmaTr = std::sqrt(3 * k.sigmaA * (k.sigmaA + k.sigmaS));
    constexpr int layers = 200;
    std::vector<double> phi(layers, 0.0), next(layers);
    for (int it = 0; it < 20000; ++it) {
      for (int i = 0; i < layers; ++i) {
        const double up = i + 1 < layers ? phi[i + 1] : 0.0, down = i > 0 ? phi[i - 1] : phi[1];  // symmetric at 0
        next[i] = a * (up + down + 4.0 * phi[i]) / 6.0 + (i == 0 ? 1.0 : 0.0);
      }
      phi.swap(next);
    }
    const double ratio = phi[21] / phi[20];
    // The recursion's decay is exact for the infinite lattice; 200 layers and 20000 iterations
    // leave it converged to ~10⁻⁷; float a costs ~10⁻⁷.
    EXPECT_NEAR(-std::log(ratio) / k.cellMm, sigmaTr, 1e-4 * sigmaTr) << "sigma_a " << k.sigmaA;
  }
}

TEST(SslpvMediumMapping, ThinCellsOnlyAbsorbAndScatteringFractionIsTheCollisionProbability) {
  // σ_t' ΔX ≪ 1: light crosses a cell along about ΔX, so a = e^{−σ_a ΔX}.
  EXPECT_NEAR(sh::sslpvSurvival(0.01f, 0.05f, 0.0f, 0.5f), std::exp(-0.005), 1e-7);
  EXPECT_FLOAT_EQ(sh::sslpvSurvival(0.0f, 0.0f, 0.0f, 3.0f), 1.0f);
  EXPECT_FLOAT_EQ(sh::sslpvSurvival(0.0f, 5.0f, 0.0f, 3.0f), 1.0f);  // no absorption: nothing lost
  EXPECT_NEAR(sh::sslpvScatteringFraction(2.0f, 0.25f), 1.0 - std::exp(-0.5), 1e-7);
  EXPECT_NEAR(std::exp(-sh::sslpvGridExtinction(0.02f, 1.0f, 0.3f, 4.0f) * 4.0f),
              sh::sslpvSurvival(0.02f, 1.0f, 0.3f, 4.0f), 1e-6);
  // Extremes stay finite: huge optical thickness, σ = 0.
  EXPECT_TRUE(std::isfinite(sh::sslpvGridExtinction(1e4f, 1e4f, 0.0f, 1e3f)));
  EXPECT_TRUE(std::isfinite(sh::sslpvGridExtinction(0.0f, 0.0f, 0.0f, 1e-4f)));
}

// --- The propagation matrices (§4) ------------------------------------------------------------------

TEST(SslpvPropagationMatrices, MatchThePaperPrintedMatrix) {
  // §4: Σ'_f M_{f,d←d±x} = [[0.167, 0, 0, ∓0.240], [0, 0.070, 0, 0], [0, 0, 0.070, 0],
  // [∓0.037, 0, 0, 0.062]]; y and z by swapping the fourth row and column with the second and third.
  // Printed to three decimals: within 0.0005 (+ 10⁻⁶ for float).
  const auto m = sslpvPropagationMatrices();
  for (int s = 0; s < 6; ++s) {
    const double sign = s % 2 == 0 ? 1.0 : -1.0;  // source at +axis or −axis
    const int axis = s / 2;                          // 0 x, 1 y, 2 z
    const int k = axis == 0 ? 3 : axis == 1 ? 1 : 2;  // the coefficient of that axis
    double paper[4][4] = {};
    paper[0][0] = 0.167;
    for (int j = 1; j < 4; ++j) paper[j][j] = j == k ? 0.062 : 0.070;
    paper[0][k] = -sign * 0.240;
    paper[k][0] = -sign * 0.037;
    for (int row = 0; row < 4; ++row)
      for (int col = 0; col < 4; ++col)
        EXPECT_NEAR(m[s][col][row], paper[row][col], 0.0005 + 1e-6) << "source " << s << " row " << row << " col " << col;
  }
}

TEST(SslpvPropagationMatrices, MatchBruteForceFaceIntegralsAndConserveFlux) {
  // M_{f,d←s} = (1/π ∫_{2π} n_f·ω y_lm dω)(∫_{Δω_{f,s}} y_l'm' dω): both factors by quadrature here,
  // the face integral over a 300 × 300 grid of the face (dω = cos θ dA/r²).
  const auto m = sslpvPropagationMatrices();
  const glm::ivec3 offsets[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  glm::dvec4 fluxRow(0.0);
  for (int s = 0; s < 6; ++s) {
    const glm::dvec3 source(offsets[s]);
    glm::dmat4 expected(0.0);
    for (int axis = 0; axis < 3; ++axis)
      for (int sign = -1; sign <= 1; sign += 2) {
        glm::dvec3 normal(0.0);
        normal[axis] = sign;
        if (normal == source) continue;
        constexpr int n = 300;
        glm::dvec4 v(0.0);
        for (int i = 0; i < n; ++i)
          for (int j = 0; j < n; ++j) {
            glm::dvec3 p(0.0);
            p[axis] = 0.5 * sign;
            p[(axis + 1) % 3] = -0.5 + (i + 0.5) / n;
            p[(axis + 2) % 3] = -0.5 + (j + 0.5) / n;
            const glm::dvec3 d = p - source;
            const double r = glm::length(d);
            v += basis(d / r) * (std::abs(d[axis]) / r / (r * r) / (n * n));
          }
        const glm::dvec4 lobe = project([&](const glm::dvec3& w) { return std::max(0.0, glm::dot(normal, w)) / kPi; });
        for (int col = 0; col < 4; ++col)
          for (int row = 0; row < 4; ++row) expected[col][row] += lobe[row] * v[col];
      }
    for (int col = 0; col < 4; ++col)
      for (int row = 0; row < 4; ++row)
        EXPECT_NEAR(m[s][col][row], expected[col][row], 1e-4) << "source " << s << " row " << row << " col " << col;
    for (int col = 0; col < 4; ++col) fluxRow[col] += m[s][col][0];
  }
  // What one cell sends to its six neighbours, Σ_s 2√π (M_s c)_0, is its whole flux 2√π c00: the
  // neighbours' 30 faces tile the sphere around it (each neighbour's five cover the 2π/3 sr of the
  // face they share). So Σ_s row 0 of M_s = (1, 0, 0, 0).
  expectNear4(fluxRow, glm::dvec4(1, 0, 0, 0), 1e-6, "flux row");
}

TEST(SslpvPropagationMatrices, PolygonProjectionMatchesQuadrature) {
  // A skew quadrilateral face seen from random points: the exact solid angle and vector solid
  // angle against 400 × 400 quadrature of the planar polygon (a parallelogram here).
  std::mt19937 rng(4);
  const glm::dvec3 o(0.2, -0.1, 0.4), e1(0.6, 0.1, 0.0), e2(0.1, 0.0, 0.5);
  const glm::dvec3 corners[4] = {o, o + e1, o + e1 + e2, o + e2};
  const glm::dvec3 normal = glm::normalize(glm::cross(e1, e2));
  const double area = glm::length(glm::cross(e1, e2));
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int t = 0; t < 4; ++t) {
    const glm::dvec3 eye(u(rng), u(rng) - 1.5, u(rng));
    glm::dvec4 numeric(0.0);
    constexpr int n = 400;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const glm::dvec3 d = o + (i + 0.5) / n * e1 + (j + 0.5) / n * e2 - eye;
        const double r = glm::length(d);
        numeric += basis(d / r) * (std::abs(glm::dot(d / r, normal)) / (r * r) * area / (n * n));
      }
    expectNear4(sslpvPolygonProjection(eye, corners, 4), numeric, 2e-5 * (1.0 + std::abs(numeric[0])), "polygon");
  }
}

TEST(SslpvSlab, LeavingFluxConvergesToTheDipoleWhileEq5CountsItNearlyThreeTimes) {
  // The marble slab (5 cm, normal incidence, E = 1) by the laterally reduced recursion, skip 0 and
  // enough steps to empty the grid, at four cell sizes. Two readings of the top layer:
  //  * the flux it passes to the vacuum above (what leaves the slab), per unit area;
  //  * Eq. 7's hemisphere (the paper's Eq. 5) times π: its estimate of the same radiosity.
  // The walk has no Fresnel reflection inside the surface (light that reaches it leaves), so its
  // limit is the dipole with A = 1 (η = 1 in Jensen's fit), not η = 1.5's A = 3.25.
  const sss::Material marble{"Marble", "", glm::vec3(2.19f, 2.62f, 3.0f), glm::vec3(0.0021f, 0.0041f, 0.0071f),
                             glm::vec3(0.0f), 1.5f};
  const double ft = test::normalTransmittance(1.5);
  double previousError = 1e9, previousOvercount = 0.0;
  for (const double cellMm : {6.25, 3.125, 1.5625, 0.78125}) {
    const int layers = static_cast<int>(std::lround(50.0 / cellMm));
    const double area = cellMm * cellMm * 1e-6;  // m²
    double worstError = 0.0, overcount = 0.0;
    for (int b = 0; b < 3; ++b) {
      const auto r = test::slabRecursion(marble.sigma_a[b], marble.sigma_s[b], 0.0f, ft * area, cellMm, layers, 8000, 0);
      const double leaving = r.escaped / area;
      const double eq5 = kPi * sh::sslpvAreaLightRadiance(sh::sslpvRotateToNormal(glm::vec4(r.top), glm::vec3(0, 1, 0)),
                                                          static_cast<float>(area), 0.0f);
      const double dipole = ft * test::jensenTotalRd(marble.sigma_a[b], marble.sigma_s[b], 0.0, 1.5);
      const double dipoleA1 = ft * test::jensenTotalRd(marble.sigma_a[b], marble.sigma_s[b], 0.0, 1.0);
      std::printf("[ sslpv ] slab %.3f mm band %d: leaving / F_t E R_d = %.3f (A = 1: %.3f), Eq. 5 / F_t E R_d = %.3f\n",
                  cellMm, b, leaving / dipole, leaving / dipoleA1, eq5 / dipole);
      worstError = std::max(worstError, std::abs(leaving / dipoleA1 - 1.0));
      overcount = std::max(overcount, eq5 / leaving);
    }
    // Each halving of the cell cuts the leaving flux's worst error by a third or more (0.76, 0.48,
    // 0.23, 0.065, the blue band): it converges.
    EXPECT_LT(worstError, 0.7 * previousError) << cellMm;
    EXPECT_GT(overcount, previousOvercount) << cellMm;  // while Eq. 5 counts more and more of it
    previousError = worstError;
    previousOvercount = overcount;
  }
  // At 0.78 mm (σ_tr ΔX ≤ 0.2): within 8% of the A = 1 dipole (2, 3.5 and 6.5% in r, g, b, still
  // converging), and Eq. 5 above 2.5 times it (an isotropic cell sends 1/2 of its flux into the
  // hemisphere but 1/6 through its face).
  EXPECT_LT(previousError, 0.08);
  EXPECT_GT(previousOvercount, 2.5);
}

TEST(SslpvGrid, CubeAroundTheBoxWithCellsAlignedOnItsLargestExtent) {
  // The slab preset's box, 0.2 × 0.05 × 0.2 m from y = 0: 32 cells of 6.25 mm whose planes include
  // the slab's faces y = 0 and y = 0.05 (12 and 20 cells above the grid's bottom).
  geometry::Aabb box;
  box.extend({-0.1f, 0.0f, -0.1f});
  box.extend({0.1f, 0.05f, 0.1f});
  const SslpvGrid g = fitSslpvGrid(box, 32);
  EXPECT_FLOAT_EQ(g.cell, 0.00625f);
  EXPECT_NEAR((0.0f - g.origin.y) / g.cell, 12.0, 1e-4);
  EXPECT_NEAR((0.05f - g.origin.y) / g.cell, 20.0, 1e-4);
  EXPECT_FLOAT_EQ(g.origin.x, -0.1f);
}

TEST(SslpvVolume, FlatLayersFillTheirFraction) {
  // turbulence 0: the second material fills fract((p·axis)/period) < fraction, so a line across
  // many layers is `fraction` of it; the noise stays in [0, 1).
  int inside = 0;
  constexpr int n = 100000;
  for (int i = 0; i < n; ++i) {
    const glm::vec3 p(0.0f, 0.37f * static_cast<float>(i) / n, 0.0f);
    inside += sh::sslpvVolumeWeight(p, glm::vec3(0, 1, 0), 0.01f, 0.3f, 0.0f, 0u) > 0.5f ? 1 : 0;
  }
  EXPECT_NEAR(static_cast<double>(inside) / n, 0.3, 0.003);  // 37 periods: the last one ±1/37·0.3
  for (int i = 0; i < 1000; ++i) {
    const float v = sh::sslpvValueNoise(glm::vec3(0.37f * i, -1.3f * i, 0.11f * i), 5u);
    EXPECT_GE(v, 0.0f);
    EXPECT_LT(v, 1.0f);
  }
}

}  // namespace
}  // namespace tallow::sss
