#pragma once
// Chandrasekhar's H-function for isotropic scattering (Chandrasekhar 1960, Radiative Transfer,
// Dover), solved from its integral equation. Used to check the planar Monte Carlo reference
// against the exact plane albedo of an index-matched, isotropically scattering half-space.
#include <vector>

namespace tallow::sss {

/// H(μ) for isotropic scattering with single-scattering albedo a ∈ [0, 1], tabulated once on
/// quadrature nodes and evaluated anywhere in μ ≥ 0 by the Nyström formula of the same equation.
class ChandrasekharH {
 public:
  /// Solves 1/H(μ) = √(1−a) + (a/2) ∫₀¹ μ' H(μ')/(μ+μ') dμ' on 240 graded Gauss–Legendre nodes
  /// by Newton's method until no nodal value moves by more than 1e-13 (also at a = 1).
  /// Throws std::invalid_argument for a ∉ [0, 1].
  explicit ChandrasekharH(double albedo);

  /// H(μ) for μ ≥ 0 (H(0) = 1). Throws std::invalid_argument for μ < 0 or NaN.
  double operator()(double mu) const;

  double albedo() const { return albedo_; }
  /// Newton iterations the solve took (a diagnostic; 4–7 for a ∈ [0.1, 1]).
  int iterations() const { return iterations_; }
  /// ∫₀¹ μⁿ H(μ) dμ by the same quadrature (n = 0: α₀, n = 1: α₁ in Chandrasekhar's notation).
  double moment(int n) const;

 private:
  double albedo_;
  int iterations_ = 0;
  std::vector<double> nodes_, weights_, values_;
};

/// H(μ) for one evaluation (solves the equation each call; keep a ChandrasekharH for many).
double chandrasekharH(double albedo, double mu);

/// Plane albedo of an index-matched, isotropically scattering half-space lit by a collimated beam
/// at direction cosine μ₀: the reflected fraction of the incident flux, 1 − H(μ₀)·√(1−a)
/// (Chandrasekhar 1960).
double isotropicPlaneAlbedo(double albedo, double mu0);

}  // namespace tallow::sss
