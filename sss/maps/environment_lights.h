#pragma once
// An environment map as M directional lights (the paper's §4 and Fig. 15): a lat-long
// (equirectangular) radiance map is cut into M regions of (nearly) equal power by median cut
// (Debevec, "A Median Cut Algorithm for Light Probe Sampling", 2005), and each region becomes one
// directional light toward its power centroid carrying the region's ∫ L dω.
//
// Mapping convention (a pixel's centre at u = (x + 0.5)/W, v = (y + 0.5)/H, +y up):
//   θ = π v (polar angle from +y: row 0 is the zenith, the last row the nadir),
//   φ = 2π (u − 0.5),
//   direction = (sin θ sin φ, cos θ, −sin θ cos φ)    (from the scene toward the environment).
// So the image's centre column looks along −z (what a camera on +z looking at the origin sees
// behind the scene), u = 0.75 is +x, u = 0.25 is −x, and the left/right edges are +z: moving right
// in the image turns right for a viewer facing −z, as when standing inside the panorama.
// `rotationDeg` then turns the environment about +y, counter-clockwise seen from above
// (right-handed): +x goes toward −z for +90°.
//
// Pixel solid angle: row y spans θ ∈ [πy/H, π(y+1)/H], so dω = (2π/W)(cos θ₀ − cos θ₁) exactly;
// the rows sum to 4π.
#include <glm/glm.hpp>

#include <vector>

#include "gpu/image.h"
#include "sss/scene.h"

namespace tallow::sss {

/// One region of the median cut and the light it becomes.
struct EnvironmentLight {
  glm::vec3 direction{0.0f, 1.0f, 0.0f};  ///< unit, toward the region's power centroid (rotated)
  glm::vec3 irradiance{0.0f};             ///< Σ L dω over the region [W/m² facing it], per band
  glm::ivec4 region{0};                   ///< pixels [x0, x1) × [y0, y1): (x0, y0, x1, y1)
  double solidAngle = 0.0;                ///< of the region [sr]
};

/// Direction of image coordinates (u, v) ∈ [0, 1]² under the convention above.
glm::dvec3 environmentDirection(double u, double v, double rotationDeg);

/// Rec. 709 luminance, the weight of the cut.
inline double environmentLuminance(const glm::vec4& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

/// Median cut of `map` (linear RGB radiance, lat-long) into at most `count` ≥ 1 regions.
/// Weight of a pixel: max(0, luminance) × dω. A region given m lights is split across its longer
/// side (azimuthal extent × sin θ of its middle row vs. polar extent) at the pixel boundary whose
/// lower part holds the fraction closest to ⌊m/2⌋/m of its weight, and the parts get ⌊m/2⌋ and
/// ⌈m/2⌉ lights; so any count works, and powers of two give Debevec's equal-power cut. A region of
/// one pixel is not split further (its lights merge into one), and regions without power give no
/// light, so fewer than `count` may come back. The direction is the normalised Σ weight × ω of the
/// region's pixels (their centres); where that sum vanishes (e.g. M = 1 on a uniform map) the
/// brightest pixel's direction is used. Negative and non-finite pixels count as 0. Sorted by
/// region solid angle, smallest (most concentrated) first.
std::vector<EnvironmentLight> medianCutEnvironment(const gpu::Image& map, int count, double rotationDeg);

/// Environment lights of at most `shadowLights` cast shadows: the most concentrated ones (the
/// smallest regions, whose shadows are sharp; a spread-out region's light would draw a hard
/// shadow it does not have). The rest have castsShadows = false.
inline constexpr int kEnvironmentShadowLights = 4;

/// medianCutEnvironment of `map` with env's count and rotation, irradiance × env.scale, as Lights.
std::vector<Light> environmentLights(const gpu::Image& map, const Environment& env);

/// Reads env.file (gpu::readHdr) and converts it; throws std::runtime_error `FILE: WHAT`.
std::vector<Light> environmentLights(const Environment& env);

}  // namespace tallow::sss
