#pragma once
// Christensen and Burley's normalised diffusion profile on the CPU (`method=burley`'s profile,
// shaders/peers/burley/profile.glsl: the same lines, compiled here in double): per colour band the
// total diffuse reflectance A and the shape parameter d a material gives, the profile, the density of
// its sampled radius, the sampling and the transmittance through a thickness. Lengths in mm.
#include <array>

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

}  // namespace tallow::sss
