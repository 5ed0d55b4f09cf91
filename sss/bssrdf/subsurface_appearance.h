#pragma once
// Materials in the terms artists and OpenPBR / MaterialX use: a subsurface colour (the total
// diffuse reflectance a thick slab shows, per band) and a radius (the mean free path, per band as
// radius × scale), with η and g, turned into σ_a and σ_s by inverting the standard dipole's total
// diffuse reflectance, as Jensen and Buhler 2002 ("A Rapid Hierarchical Rendering Technique for
// Translucent Materials": the artist gives R_d and the mean free path ℓ_d; α' follows from R_d,
// σ_t' = 1/ℓ_d) do. The inverse (appearanceOf) gives back the colour and radius of any material.
#include <glm/glm.hpp>

#include "sss/bssrdf/material.h"

namespace tallow::sss {

struct SubsurfaceAppearance {
  glm::vec3 color{0.8f};            ///< subsurface_color: total diffuse reflectance per band, [0, 1]
  float radiusMm = 1.0f;            ///< subsurface_radius_mm: mean free path 1/σ_t' [mm], > 0
  glm::vec3 radiusScale{1.0f};      ///< subsurface_radius_scale: per band, > 0
  float eta = 1.3f;                 ///< relative index of refraction
  glm::vec3 g{0.0f};                ///< Henyey–Greenstein mean cosine, |g| < 1
};

/// The reduced albedo α' ∈ [0, 1] whose standard-dipole total reflectance at η is `reflectance`
/// (bisection; R_d rises with α' from 0 to 1). Throws std::invalid_argument outside [0, 1].
double reducedAlbedoFor(double reflectance, double eta);

/// σ_t' = 1/(radius × scale), σ_s' = α' σ_t', σ_a = σ_t' − σ_s', σ_s = σ_s'/(1 − g). Throws
/// std::invalid_argument with one line naming the value when one is out of range.
Material materialFromAppearance(const SubsurfaceAppearance& a);

/// The colour (the dipole's total of each band's α') and radius (1/σ_t' of the band that reaches
/// farthest, the others as scales) of `m`.
SubsurfaceAppearance appearanceOf(const Material& m);

}  // namespace tallow::sss
