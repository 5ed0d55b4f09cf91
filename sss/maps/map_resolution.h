#pragma once
// The sizes that "auto" chooses for the scattered radiosity maps (sss.map_size) and the light
// G-buffers (sss.light_map_size), and the widest footprint Algorithm 1 filters the maps over
// (issue 17, point 4: only what the scene needs). Measured in docs/RESULTS.md ("Map sizes from the
// scene"), by scripts/results_auto.py.
//
// - A map texel should be no wider than half of what the camera resolves there: half a pixel of the
//   bounding sphere's projection, so twice the sphere's diameter in pixels (B is interpolated between
//   texel centres). And no wider than the diffusion length 1/σ_tr where B changes: the sphere's
//   diameter over the shortest 1/σ_tr. The larger of the two counts, as a power of two in
//   [kAutoMapMin, kAutoMapMax]; the screen's count at most the paper's 512 (kAutoMapScreenMax: "a
//   size of 512 x 512 is fine for most application", §5), only the diffusion length asks for more.
// - A light G-buffer texel should be a quarter of the shortest 1/σ_tr (the paper's §5 pearling
//   appears at one 1/σ_tr; its figures use 512, "1024 in problematic cases"), at least 512 (the
//   paper's size) and at most 4096 for directional lights, 1024 for point lights (a cube of six faces).
#include "sss/maps/radiosity_maps.h"
#include "sss/scene.h"

namespace tallow::sss {

constexpr int kAutoMapMin = 128;
constexpr int kAutoMapMax = 2048;
constexpr int kAutoMapScreenMax = 512;
constexpr int kAutoLightMin = 512;
constexpr int kAutoLightMax = 4096;
constexpr int kAutoPointLightMax = 1024;

/// The smallest power of two ≥ x, within [lo, hi] (lo and hi powers of two).
int powerOfTwoAtLeast(double x, int lo, int hi);

/// The sphere's diameter in pixels of an image `height` pixels tall: perspective 2r / (2 d tan(fov/2))
/// × height with d the distance from the camera to the sphere's centre (at least r), orthographic
/// 2r / orthoHeight × height. Screen coverage, as one length.
double projectedDiameterPixels(const Camera& camera, int height, const BoundingSphere& sphere);

/// sss.map_size=auto: powerOfTwoAtLeast(max(min(2 × pixels, 512), diameter / shortest 1/σ_tr)) in
/// [kAutoMapMin, min(kAutoMapMax, maxSize)].
int autoMapSize(double diameterMm, double shortestDiffusionMm, double projectedPixels, int maxSize);
/// sss.light_map_size=auto: powerOfTwoAtLeast(4 × diameter / shortest 1/σ_tr) in [kAutoLightMin,
/// min(kAutoLightMax or, with a point light, kAutoPointLightMax, maxSize)].
int autoLightMapSize(double diameterMm, double shortestDiffusionMm, bool pointLight, int maxSize);

/// Algorithm 1's uMaxFootprint for the camera's look-ups, in map texture units (a map spans the
/// views' sphere diameter): half the shortest 1/σ_tr.
float maxMapFootprint(double shortestDiffusionMm, float viewSphereRadiusM);

}  // namespace tallow::sss
