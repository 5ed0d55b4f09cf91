#include "sss/reference/chandrasekhar_h.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace tallow::sss {

namespace {

/// Gauss–Legendre points per panel. With the graded panels below, H agrees with its independent
/// exponential-integral representation to 1e-10 for μ ∈ [1e-3, 1] and α₀ with its closed form to
/// 1e-11 (tests/planar_mc_test.cpp).
constexpr int kPointsPerPanel = 20;
/// Panel edges on [0, 1], graded geometrically toward 0: H has a μ·ln μ term there and the kernel
/// μ'/(μ+μ') varies on the scale μ' ~ μ, so small μ need small panels.
constexpr std::array<double, 13> kPanelEdges = {0.0,  1e-7, 1e-6, 1e-5, 1e-4, 1e-3, 1e-2,
                                                0.05, 0.1,  0.2,  0.4,  0.7,  1.0};
/// Convergence of the Newton iteration: largest change of a nodal value.
constexpr double kTolerance = 1e-13;
constexpr int kMaxIterations = 100;

/// Nodes and weights of the n-point Gauss–Legendre rule on [-1, 1] (Newton on P_n from the
/// Chebyshev-like initial guess; Abramowitz & Stegun 25.4.29).
void gaussLegendre(int n, std::vector<double>& x, std::vector<double>& w) {
  x.assign(static_cast<std::size_t>(n), 0.0);
  w.assign(static_cast<std::size_t>(n), 0.0);
  for (int i = 0; i < n; ++i) {
    double z = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
    double dp = 0.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = z;  // P_0, P_1
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (z * p1 - p0) / (z * z - 1.0);  // P_n'(z)
      const double dz = p1 / dp;
      z -= dz;
      if (std::abs(dz) < 1e-16) break;
    }
    x[static_cast<std::size_t>(i)] = z;
    w[static_cast<std::size_t>(i)] = 2.0 / ((1.0 - z * z) * dp * dp);
  }
}

/// Solves A·x = b for a dense n×n row-major A by Gaussian elimination with partial pivoting;
/// b is replaced by x, A is destroyed.
void solveInPlace(std::vector<double>& a, std::vector<double>& b, std::size_t n) {
  for (std::size_t col = 0; col < n; ++col) {
    std::size_t pivot = col;
    for (std::size_t r = col + 1; r < n; ++r)
      if (std::abs(a[r * n + col]) > std::abs(a[pivot * n + col])) pivot = r;
    if (pivot != col) {
      for (std::size_t k = 0; k < n; ++k) std::swap(a[col * n + k], a[pivot * n + k]);
      std::swap(b[col], b[pivot]);
    }
    const double inv = 1.0 / a[col * n + col];
    for (std::size_t r = col + 1; r < n; ++r) {
      const double f = a[r * n + col] * inv;
      if (f == 0.0) continue;
      for (std::size_t k = col; k < n; ++k) a[r * n + k] -= f * a[col * n + k];
      b[r] -= f * b[col];
    }
  }
  for (std::size_t r = n; r-- > 0;) {
    double s = b[r];
    for (std::size_t k = r + 1; k < n; ++k) s -= a[r * n + k] * b[k];
    b[r] = s / a[r * n + r];
  }
}

/// (a/2) Σ_j w_j μ_j H_j / (μ + μ_j): the integral of the H equation by quadrature.
double kernelSum(double albedo, double mu, const std::vector<double>& nodes, const std::vector<double>& weights,
                 const std::vector<double>& values) {
  double sum = 0.0;
  for (std::size_t j = 0; j < nodes.size(); ++j) sum += weights[j] * nodes[j] * values[j] / (mu + nodes[j]);
  return 0.5 * albedo * sum;
}

}  // namespace

ChandrasekharH::ChandrasekharH(double albedo) : albedo_(albedo) {
  if (!(albedo >= 0.0 && albedo <= 1.0))
    throw std::invalid_argument("H-function albedo must be in [0, 1] (" + std::to_string(albedo) + ")");
  std::vector<double> x, w;
  gaussLegendre(kPointsPerPanel, x, w);
  for (std::size_t p = 0; p + 1 < kPanelEdges.size(); ++p) {
    const double lo = kPanelEdges[p], hi = kPanelEdges[p + 1];
    for (int i = 0; i < kPointsPerPanel; ++i) {
      nodes_.push_back(lo + 0.5 * (hi - lo) * (x[static_cast<std::size_t>(i)] + 1.0));
      weights_.push_back(0.5 * (hi - lo) * w[static_cast<std::size_t>(i)]);
    }
  }
  // Newton's method on the discretised second form 1/H = √(1−a) + (a/2)∫ μ'H(μ')/(μ+μ') dμ'
  // (Chandrasekhar 1960), written as F_i = H_i·(√(1−a) + (a/2)Σ_j c_ij H_j) − 1 = 0 with
  // c_ij = w_j μ_j/(μ_i+μ_j). Plain fixed-point iteration converges only algebraically at a = 1
  // (the conservative case), Newton quadratically at every a.
  const double root = std::sqrt(1.0 - albedo);
  const std::size_t n = nodes_.size();
  std::vector<double> c(n * n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) c[i * n + j] = weights_[j] * nodes_[j] / (nodes_[i] + nodes_[j]);
  values_.assign(n, 1.0);
  std::vector<double> jac(n * n), rhs(n);
  for (iterations_ = 1; iterations_ <= kMaxIterations; ++iterations_) {
    for (std::size_t i = 0; i < n; ++i) {
      double s = 0.0;
      for (std::size_t j = 0; j < n; ++j) s += c[i * n + j] * values_[j];
      const double denominator = root + 0.5 * albedo * s;
      rhs[i] = -(values_[i] * denominator - 1.0);
      for (std::size_t k = 0; k < n; ++k) jac[i * n + k] = 0.5 * albedo * values_[i] * c[i * n + k];
      jac[i * n + i] += denominator;
    }
    solveInPlace(jac, rhs, n);
    double change = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      values_[i] += rhs[i];
      change = std::max(change, std::abs(rhs[i]));
    }
    if (change < kTolerance) return;
  }
  throw std::runtime_error("H-function iteration did not converge for albedo " + std::to_string(albedo));
}

double ChandrasekharH::operator()(double mu) const {
  if (!(mu >= 0.0)) throw std::invalid_argument("H-function argument must be >= 0 (" + std::to_string(mu) + ")");
  if (mu == 0.0) return 1.0;  // the kernel μ'/(μ+μ') is 1 there; the sum would give 1/(√(1−a) + a/2·α₀) = 1
  return 1.0 / (std::sqrt(1.0 - albedo_) + kernelSum(albedo_, mu, nodes_, weights_, values_));
}

double ChandrasekharH::moment(int n) const {
  double sum = 0.0;
  for (std::size_t j = 0; j < nodes_.size(); ++j) sum += weights_[j] * std::pow(nodes_[j], n) * values_[j];
  return sum;
}

double chandrasekharH(double albedo, double mu) { return ChandrasekharH(albedo)(mu); }

double isotropicPlaneAlbedo(double albedo, double mu0) {
  return 1.0 - ChandrasekharH(albedo)(mu0) * std::sqrt(1.0 - albedo);
}

}  // namespace tallow::sss
