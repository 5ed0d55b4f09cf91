#pragma once
// The BSSRDF models on the CPU: the C++ face of the shared model files shaders/bssrdf/*.glsl,
// which the GPU passes compile as GLSL. Standard dipole (Jensen et al. 2001), directional dipole
// (Frisvad et al. 2014) and photon beam diffusion (Habel et al. 2013), each evaluated in float or
// double by the same lines. Formulas and conventions: docs/bssrdf-models.md. No OpenGL here
// (the GPU path is sss/bssrdf/bssrdf_gpu.h).
#include <glm/glm.hpp>

#include <string_view>

namespace tallow::sss {

enum class BssrdfModel { Standard = 0, Directional = 1, PhotonBeamDiffusion = 2 };

/// "standard" | "directional" | "pbd"; throws std::invalid_argument (one line naming the choices).
BssrdfModel parseBssrdfModel(std::string_view name);
/// The name parseBssrdfModel accepts.
std::string_view bssrdfModelName(BssrdfModel model);

/// One evaluation of S_d(x_i, w_i; x_o) for one colour band. Lengths in mm, coefficients in mm⁻¹;
/// ni, no outward unit normals; wi the unit vector from x_i toward the light (wi·ni > 0 when x_i
/// is lit from outside); eta the relative index of refraction (inside / outside).
struct BssrdfConfig {
  glm::dvec3 xi, ni, wi, xo, no;
  double sigma_a, sigma_s, g, eta;
};

/// The diffusive part S_d [mm⁻²] as the model gives it (`sd`, may be negative) and clamped to
/// ≥ 0 as a renderer uses it (`sdClamped`, §6.1 of the directional-dipole paper). Fresnel
/// transmittances are not included.
struct BssrdfValue {
  double sd;
  double sdClamped;
};

/// Photon beam diffusion: Gauss–Legendre panels (8 nodes each) per e-fold of the distance to the
/// nearest singularity of the beam integral; the default agrees with 8 panels per e-fold to < 1e-9
/// of the integral's scale (shaders/bssrdf/photon_beam_diffusion.glsl, docs/bssrdf-models.md).
inline constexpr int kPbdDefaultPanelsPerEfold = 2;

struct BssrdfOptions {
  bool reciprocal = false;  ///< average with the swapped evaluation (§6.3; docs/bssrdf-models.md)
  int pbdPanelsPerEfold = kPbdDefaultPanelsPerEfold;  ///< ≥ 1; photon beam diffusion only
};

/// Evaluates `model` in precision Real (float: the inputs are converted to float and the float
/// instantiation of the shared code runs). Does not validate the configuration: call
/// validateBssrdfConfig first on untrusted input. Finite for every valid configuration
/// (tests/bssrdf_stability_test.cpp). Throws std::invalid_argument for pbdPanelsPerEfold < 1.
template <class Real>
BssrdfValue evaluateBssrdf(BssrdfModel model, const BssrdfConfig& config, bool reciprocal = false);
template <class Real>
BssrdfValue evaluateBssrdf(BssrdfModel model, const BssrdfConfig& config, const BssrdfOptions& options);

extern template BssrdfValue evaluateBssrdf<float>(BssrdfModel, const BssrdfConfig&, bool);
extern template BssrdfValue evaluateBssrdf<double>(BssrdfModel, const BssrdfConfig&, bool);
extern template BssrdfValue evaluateBssrdf<float>(BssrdfModel, const BssrdfConfig&, const BssrdfOptions&);
extern template BssrdfValue evaluateBssrdf<double>(BssrdfModel, const BssrdfConfig&, const BssrdfOptions&);

/// The scale of S_d's rounding error, in double: the sum of the absolute values of the terms whose
/// signed sum is S_d (the four terms of Eq. 20's bracket for the real and the virtual source; for
/// PBD every term at every quadrature node). Equals |S_d| for the standard dipole; can be far above
/// |S_d| where terms cancel.
double bssrdfMagnitude(BssrdfModel model, const BssrdfConfig& config, const BssrdfOptions& options = {});

/// Throws std::invalid_argument, one line naming the field, unless: every value is finite;
/// sigma_a, sigma_s ≥ 0 and sigma_a + sigma_s > 0; |g| < 1; eta > 0; ni, no and wi have length
/// within 1e-3 of 1.
void validateBssrdfConfig(const BssrdfConfig& config);

/// The input ranges validateBssrdfConfig accepts beyond the physical constraints: coefficients up
/// to 1e6 mm⁻¹, a reduced extinction σ_a + (1 − g)σ_s of at least 1e-30 mm⁻¹ (a transport mean
/// free path of 1e21 km; below about 1e-150 mm⁻¹ the models' powers of 1/σ_t' overflow double and
/// S_d turns NaN, found by fuzz_bssrdf_csv), η in [1e-3, 1e3], positions within 1e6 mm of the origin.
inline constexpr double kMaxCoefficient = 1e6;
inline constexpr double kMinReducedExtinction = 1e-30;
inline constexpr double kMaxEta = 1e3;
inline constexpr double kMaxPosition = 1e6;

/// Quantities derived from the optical properties (shaders/bssrdf/coefficients.glsl), in double.
struct BssrdfCoefficients {
  double sigma_t;           ///< σ_t = σ_a + σ_s
  double sigma_s_reduced;   ///< σ_s' = σ_s (1 − g)
  double sigma_t_reduced;   ///< σ_t' = σ_a + σ_s'
  double albedo_reduced;    ///< α' = σ_s'/σ_t'
  double D;                 ///< 1/(3σ_t')
  double sigma_tr;          ///< √(σ_a/D)
  double d_e;               ///< 2.131 D/√α' (Eq. 21)
  double c_phi;             ///< C_φ(η), polynomial fit (appendix A)
  double c_e;               ///< C_E(η), polynomial fit
  double c_phi_inv;         ///< C_φ(1/η)
  double A;                 ///< (1 − C_E)/(2C_φ) (Eq. 22): directional dipole and PBD
  double A_jensen;          ///< (1 + F_dr)/(1 − F_dr), F_dr fit of Jensen et al.: standard dipole
  double z_r, z_v;          ///< standard dipole source depth and image height
  double D_grosjean;        ///< (2σ_a + σ_s')/(3σ_t'²): PBD
  double sigma_tr_grosjean; ///< √(σ_a/D_G): PBD
  double z_b;               ///< 2A D_G: PBD extrapolated boundary
  double pbd_min_distance;  ///< 0.25/(σ_a + σ_t): PBD clamp of d_r
};
BssrdfCoefficients bssrdfCoefficients(double sigma_a, double sigma_s, double g, double eta);

/// The standard dipole's total diffuse reflectance ∫ R_d 2πr dr (Jensen et al. 2001) of a medium of
/// reduced albedo α' ∈ [0, 1] behind a boundary of relative index η (shaders/bssrdf/standard_dipole.glsl).
double dipoleTotalReflectance(double reducedAlbedo, double eta);

/// C_φ(η), C_E(η) from the polynomial fits (appendix A; η clamped to [0.4, 2.5]) …
double cPhiPolynomial(double eta);
double cEPolynomial(double eta);
/// … and by numerical integration of Eqs. 28–29 (adaptive Gauss–Kronrod, error < 1e-12).
double cPhiIntegrated(double eta);
double cEIntegrated(double eta);

/// Exact unpolarised dielectric Fresnel reflectance / transmittance; cosTheta on the side the light
/// comes from (sign ignored), eta = η_transmitted/η_incident; total internal reflection gives R = 1.
double fresnelReflectance(double cosTheta, double eta);
double fresnelTransmittance(double cosTheta, double eta);

}  // namespace tallow::sss
