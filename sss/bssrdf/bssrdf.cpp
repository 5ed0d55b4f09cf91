#include "sss/bssrdf/bssrdf.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "gpu/glsl_shared.h"  // TALLOW_FN and GLM's GLSL vocabulary; no OpenGL

// The shared model files, compiled once per precision. Each namespace supplies the types that
// shaders/bssrdf/real.glsl defines as macros in GLSL, then includes every file in dependency order.
namespace tallow::sss::shared_f32 {
using real = float;
#include "gpu/glsl_real_types.inc"
#include "sss/bssrdf/bssrdf_models.inc"
}  // namespace tallow::sss::shared_f32

namespace tallow::sss::shared_f64 {
using real = double;
#include "gpu/glsl_real_types.inc"
#include "sss/bssrdf/bssrdf_models.inc"
}  // namespace tallow::sss::shared_f64

namespace tallow::sss {

static_assert(static_cast<int>(BssrdfModel::Standard) == shared_f64::BSSRDF_MODEL_STANDARD);
static_assert(static_cast<int>(BssrdfModel::Directional) == shared_f64::BSSRDF_MODEL_DIRECTIONAL);
static_assert(static_cast<int>(BssrdfModel::PhotonBeamDiffusion) == shared_f64::BSSRDF_MODEL_PBD);
static_assert(kPbdDefaultPanelsPerEfold == shared_f64::PBD_DEFAULT_PANELS_PER_EFOLD);

namespace {

struct RawEval {
  double sd, scale;
};

/// Runs the shared entry point (shared_f32 for float, shared_f64 for double) on the configuration
/// converted to Real.
template <class Real>
RawEval evaluateShared(BssrdfModel model, const BssrdfConfig& c, const BssrdfOptions& o) {
  if (o.pbdPanelsPerEfold < 1)
    throw std::invalid_argument("pbdPanelsPerEfold must be at least 1 (" + std::to_string(o.pbdPanelsPerEfold) + ")");
  auto run = [&](auto coefficients, auto evaluate, auto evaluateReciprocal, auto toVec) {
    const auto k = coefficients(Real(c.sigma_a), Real(c.sigma_s), Real(c.g), Real(c.eta));
    const int m = static_cast<int>(model);
    const auto e = o.reciprocal
                       ? evaluateReciprocal(m, toVec(c.xi), toVec(c.ni), toVec(c.wi), toVec(c.xo), toVec(c.no), k,
                                            o.pbdPanelsPerEfold)
                       : evaluate(m, toVec(c.xi), toVec(c.ni), toVec(c.wi), toVec(c.xo), toVec(c.no), k,
                                  o.pbdPanelsPerEfold);
    return RawEval{static_cast<double>(e.sd), static_cast<double>(e.scale)};
  };
  if constexpr (std::is_same_v<Real, float>) {
    namespace s = shared_f32;
    return run([](float a, float b, float g, float n) { return s::bssrdfCoefficients(a, b, g, n); },
               [](auto... a) { return s::bssrdfEvaluate(a...); },
               [](auto... a) { return s::bssrdfEvaluateReciprocal(a...); },
               [](const glm::dvec3& v) { return glm::vec3(v); });
  } else {
    static_assert(std::is_same_v<Real, double>, "evaluateBssrdf: float or double");
    namespace s = shared_f64;
    return run([](double a, double b, double g, double n) { return s::bssrdfCoefficients(a, b, g, n); },
               [](auto... a) { return s::bssrdfEvaluate(a...); },
               [](auto... a) { return s::bssrdfEvaluateReciprocal(a...); },
               [](const glm::dvec3& v) { return v; });
  }
}

std::string formatNumber(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

/// Adaptive 15-point Gauss–Kronrod quadrature of f on [a, b] to absolute error `tol`.
template <class F>
double integrateGaussKronrod(const F& f, double a, double b, double tol, int depth = 0) {
  static constexpr double xk[8] = {0.991455371120812639, 0.949107912342758525, 0.864864423359769073,
                                   0.741531185599394440, 0.586087235467691130, 0.405845151377397167,
                                   0.207784955007898468, 0.0};
  static constexpr double wk[8] = {0.022935322010529225, 0.063092092629978553, 0.104790010322250184,
                                   0.140653259715525919, 0.169004726639267903, 0.190350578064785410,
                                   0.204432940075298892, 0.209482141084727828};
  static constexpr double wg[4] = {0.129484966168869693, 0.279705391489276668, 0.381830050505118945,
                                   0.417959183673469388};  // Gauss nodes are xk[1], xk[3], xk[5], xk[7]
  const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
  double kronrod = wk[7] * f(mid), gauss = wg[3] * f(mid);
  for (int i = 0; i < 7; ++i) {
    const double fs = f(mid - half * xk[i]) + f(mid + half * xk[i]);
    kronrod += wk[i] * fs;
    if (i % 2 == 1) gauss += wg[i / 2] * fs;
  }
  kronrod *= half;
  gauss *= half;
  if (std::abs(kronrod - gauss) <= tol || depth >= 40) return kronrod;
  return integrateGaussKronrod(f, a, mid, 0.5 * tol, depth + 1) +
         integrateGaussKronrod(f, mid, b, 0.5 * tol, depth + 1);
}

/// ∫₀¹ T(μ; 1/η) μ^power dμ over the cosine μ inside the medium (Eqs. 28–29 up to their constants).
/// For η > 1, T = 0 below the critical cosine μ_c and T ∝ √(μ − μ_c) above it; μ = μ_c + (1 − μ_c)s²
/// makes the integrand smooth.
double fresnelMomentIntegral(double eta, int power) {
  const double muC = eta > 1.0 ? std::sqrt(1.0 - 1.0 / (eta * eta)) : 0.0;
  const auto integrand = [&](double s) {
    const double mu = muC + (1.0 - muC) * s * s;
    return shared_f64::fresnelTransmittance(mu, 1.0 / eta) * std::pow(mu, power) * 2.0 * (1.0 - muC) * s;
  };
  return integrateGaussKronrod(integrand, 0.0, 1.0, 1e-14);
}

}  // namespace

BssrdfModel parseBssrdfModel(std::string_view name) {
  if (name == "standard") return BssrdfModel::Standard;
  if (name == "directional") return BssrdfModel::Directional;
  if (name == "pbd") return BssrdfModel::PhotonBeamDiffusion;
  throw std::invalid_argument("unknown BSSRDF model \"" + std::string(name) + "\" (standard, directional, pbd)");
}

std::string_view bssrdfModelName(BssrdfModel model) {
  switch (model) {
    case BssrdfModel::Standard: return "standard";
    case BssrdfModel::Directional: return "directional";
    case BssrdfModel::PhotonBeamDiffusion: return "pbd";
  }
  return "?";
}

template <class Real>
BssrdfValue evaluateBssrdf(BssrdfModel model, const BssrdfConfig& config, const BssrdfOptions& options) {
  const RawEval e = evaluateShared<Real>(model, config, options);
  return BssrdfValue{e.sd, std::max(e.sd, 0.0)};
}

template <class Real>
BssrdfValue evaluateBssrdf(BssrdfModel model, const BssrdfConfig& config, bool reciprocal) {
  BssrdfOptions options;
  options.reciprocal = reciprocal;
  return evaluateBssrdf<Real>(model, config, options);
}

template BssrdfValue evaluateBssrdf<float>(BssrdfModel, const BssrdfConfig&, bool);
template BssrdfValue evaluateBssrdf<double>(BssrdfModel, const BssrdfConfig&, bool);
template BssrdfValue evaluateBssrdf<float>(BssrdfModel, const BssrdfConfig&, const BssrdfOptions&);
template BssrdfValue evaluateBssrdf<double>(BssrdfModel, const BssrdfConfig&, const BssrdfOptions&);

double bssrdfMagnitude(BssrdfModel model, const BssrdfConfig& config, const BssrdfOptions& options) {
  return evaluateShared<double>(model, config, options).scale;
}

void validateBssrdfConfig(const BssrdfConfig& c) {
  const auto fail = [](const std::string& message) { throw std::invalid_argument(message); };
  const struct {
    const char* name;
    const glm::dvec3& v;
  } vectors[] = {{"xi", c.xi}, {"ni", c.ni}, {"wi", c.wi}, {"xo", c.xo}, {"no", c.no}};
  for (const auto& [name, v] : vectors)
    for (int i = 0; i < 3; ++i)
      if (!std::isfinite(v[i]))
        fail(std::string(name) + "_" + "xyz"[i] + " is not finite (" + formatNumber(v[i]) + ")");
  const struct {
    const char* name;
    double v;
  } scalars[] = {{"sigma_a", c.sigma_a}, {"sigma_s", c.sigma_s}, {"g", c.g}, {"eta", c.eta}};
  for (const auto& [name, v] : scalars)
    if (!std::isfinite(v)) fail(std::string(name) + " is not finite (" + formatNumber(v) + ")");
  if (c.sigma_a < 0.0) fail("sigma_a is negative (" + formatNumber(c.sigma_a) + ")");
  if (c.sigma_s < 0.0) fail("sigma_s is negative (" + formatNumber(c.sigma_s) + ")");
  if (c.sigma_a + c.sigma_s <= 0.0) fail("sigma_a + sigma_s is 0: the medium neither scatters nor absorbs");
  if (!(std::abs(c.g) < 1.0)) fail("g is outside (-1, 1) (" + formatNumber(c.g) + ")");
  if (!(c.eta > 0.0)) fail("eta is not positive (" + formatNumber(c.eta) + ")");
  // Bounds far beyond any material or scene (1e6 mm⁻¹ is a mean free path of a nanometre; 1e6 mm
  // is a kilometre) but inside what the models evaluate finitely in double precision.
  if (c.sigma_a > kMaxCoefficient || c.sigma_s > kMaxCoefficient)
    fail("sigma_a and sigma_s must be at most " + formatNumber(kMaxCoefficient) + " /mm");
  if (!(c.sigma_a + (1.0 - c.g) * c.sigma_s >= kMinReducedExtinction))
    fail("sigma_a + (1 - g) sigma_s must be at least " + formatNumber(kMinReducedExtinction) + " /mm (" +
         formatNumber(c.sigma_a + (1.0 - c.g) * c.sigma_s) + ")");
  if (c.eta > kMaxEta || c.eta < 1.0 / kMaxEta)
    fail("eta must be in [" + formatNumber(1.0 / kMaxEta) + ", " + formatNumber(kMaxEta) + "]");
  for (const auto& [name, v] : vectors)
    if (name[0] == 'x' && glm::length(v) > kMaxPosition)
      fail(std::string(name) + " is more than " + formatNumber(kMaxPosition) + " mm from the origin");
  for (const auto& [name, v] : vectors) {
    if (name[0] == 'x') continue;
    const double length = glm::length(v);
    if (!(std::abs(length - 1.0) <= 1e-3))
      fail(std::string(name) + " is not a unit vector (length " + formatNumber(length) + ")");
  }
}

double dipoleTotalReflectance(double reducedAlbedo, double eta) {
  // Any σ_t' will do: the total depends on α' and η alone.
  return shared_f64::standardDipoleTotalRd(shared_f64::bssrdfCoefficients(1.0 - reducedAlbedo, reducedAlbedo, 0.0, eta));
}

BssrdfCoefficients bssrdfCoefficients(double sigma_a, double sigma_s, double g, double eta) {
  const shared_f64::BssrdfCoefficients k = shared_f64::bssrdfCoefficients(sigma_a, sigma_s, g, eta);
  BssrdfCoefficients out;
  out.sigma_t = k.sigmaT;
  out.sigma_s_reduced = k.sigmaSp;
  out.sigma_t_reduced = k.sigmaTp;
  out.albedo_reduced = k.alphaP;
  out.D = k.D;
  out.sigma_tr = k.sigmaTr;
  out.d_e = k.de;
  out.c_phi = k.cPhi;
  out.c_e = k.cE;
  out.c_phi_inv = k.cPhiInv;
  out.A = k.A;
  out.A_jensen = k.aJensen;
  out.z_r = k.zr;
  out.z_v = k.zv;
  out.D_grosjean = k.Dg;
  out.sigma_tr_grosjean = k.sigmaTrG;
  out.z_b = k.zb;
  out.pbd_min_distance = k.pbdMinDistance;
  return out;
}

double cPhiPolynomial(double eta) { return shared_f64::cPhiPolynomial(eta); }
double cEPolynomial(double eta) { return shared_f64::cEPolynomial(eta); }
double cPhiIntegrated(double eta) { return 0.5 * fresnelMomentIntegral(eta, 1); }
double cEIntegrated(double eta) { return 1.5 * fresnelMomentIntegral(eta, 2); }

double fresnelReflectance(double cosTheta, double eta) { return shared_f64::fresnelReflectance(cosTheta, eta); }
double fresnelTransmittance(double cosTheta, double eta) { return shared_f64::fresnelTransmittance(cosTheta, eta); }

}  // namespace tallow::sss
