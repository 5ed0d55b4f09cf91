#pragma once
// Christensen and Burley's normalised diffusion profile on the CPU (`method=burley`'s profile,
// shaders/peers/burley/profile.glsl: the same lines, compiled here in double): per colour band the
// total diffuse reflectance A and the shape parameter d a material gives, the profile, the density of
// its sampled radius, the sampling and the transmittance through a thickness. Lengths in mm.
#include <array>
#include <vector>

#include "sss/bssrdf/material.h"

namespace tallow::sss {

struct BurleyBandParams {
  double albedo = 0.0;  ///< A = ∫ R 2πr dr, the standard dipole's total diffuse reflectance
  double d = 0.0;       ///< [mm] ℓ / s(A), ℓ = 1/σ_t'
};

/// A and d of each colour band of `m`.
std::array<BurleyBandParams, 3> burleyBands(const Material& m);
/// The profile R(r) [mm⁻²] at r > 0 [mm].
double burleyProfile(double r, const BurleyBandParams& band);
/// The density of the sampled radius [mm⁻¹].
double burleyRadiusPdf(double r, double d);
/// A radius from two uniform numbers in [0, 1).
double burleySampleRadius(double u1, double u2, double d);
/// The share of the irradiance that crosses a thickness t [mm].
double burleyTransmittance(double t, const BurleyBandParams& band);
/// The memo's fit s(A) (searchlight configuration, mean free path).
double burleyScale(double albedo);

/// The share of the profile's mass beyond the line x = a ≥ 0 [mm] of the plane:
/// ∫_a^∞ (R(r)/A) 2r acos(a/r) dr (the arc of each circle beyond the line); 1/2 at a = 0.
double burleyHalfPlaneMass(double a, double d);

/// The separable kernel (Jimenez et al. 2015's structure with this profile, `burley.kernel=separable`):
/// taps at offsets t_k = R (k/K)² for k = −K … K along a line, R = kBurleySeparableRadius · d_max,
/// each weighing the profile's mass in its strip of the plane (between the midpoints to its
/// neighbours; the outermost strips reach to infinity), per band, so that each band's weights sum
/// to 1 and a horizontal pass then a vertical one give the profile's 2D mass on a uniform image.
struct BurleyTap {
  double offset = 0.0;              ///< t_k [mm]
  std::array<double, 3> weight{};   ///< per band
};
inline constexpr double kBurleySeparableRadius = 8.0;
/// Taps for k = 0 … K (the kernel is symmetric: negative k mirror positive ones), K ≥ 1.
std::vector<BurleyTap> burleySeparableTaps(const std::array<BurleyBandParams, 3>& bands, int halfTaps);

}  // namespace tallow::sss
