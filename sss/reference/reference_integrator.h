#pragma once
// The CPU ground truth (`tallow reference`, issue 6): the image `capture` renders, computed by
// direct Monte Carlo integration of the BSSRDF over the translucent objects' surfaces as in the
// directional-dipole paper (§4) — points spread over each surface by area, each lit through shadow
// rays, summed with the shared S_d (sss/bssrdf/bssrdf.h) into the scattered radiosity B of the
// radiosity-maps paper's Eq. 7 — and Lambertian opaque surfaces with hard shadows. Rays: Embree 3;
// threads: TBB. Progressive: passes of fresh points, a per-pixel mean and variance over passes, and
// a stop on a pass count or a relative standard error. Optionally (emergentLight) the light leaving
// the translucent objects lands on the opaque receivers, one bounce (the ground truth for the
// VPLs of the radiosity-maps paper's §3.4). Formulas and limitations: docs/reference.md.
#include <cstdint>
#include <functional>
#include <map>
#include <string>

#include "geometry/triangle_mesh.h"

#include "gpu/image.h"
#include "sss/render_settings.h"
#include "sss/scene.h"

namespace tallow::sss {

/// The default of ReferenceSettings::emitterPoints: each pass costs receiver pixels × emitter
/// points shadow rays, so the count is bounded rather than scaled with the area.
inline constexpr int kDefaultEmitterPoints = 1024;

/// The default of ReferenceSettings::minPasses.
inline constexpr int kDefaultMinPasses = 8;

/// Field objects' triangles by object index, in the field's own units (before its transform).
using FieldMeshes = std::map<int, geometry::TriangleMesh>;

/// What a pixel's value is the mean of: the scene along the ray through its centre, or over its
/// square (a box filter: pass k traces sub-pixel position k of sss/pixel_jitter.h, as the GPU's
/// still average, render.aa, draws frame k of a still).
enum class PixelFilter { Centre, Box };

struct ReferenceSettings {
  double timeS = 0.0;           ///< animation time: field objects meshed and flame lights placed at t
  int maxPasses = 0;            ///< stop after this many passes (0: no pass limit)
  double relError = 0.0;        ///< stop once the relative standard error is at most this (0: off)
  /// M, surface points per translucent object and pass (≥ 1); 0: per object, enough for
  /// kNearFieldTarget expected points per pass within 1/σ_t' of each x_o (see nearFieldPoints).
  int pointsPerPass = 0;
  std::uint64_t seed = 1;       ///< the random stream; results do not depend on the thread count
  int threads = 0;              ///< 0: TBB's default
  /// Centre: the integrator's estimate at the pixel centres (its tests compare points with analytic
  /// values); `tallow reference` and the bench take Box, to compare with anti-aliased stills.
  PixelFilter pixelFilter = PixelFilter::Centre;
  int minPasses = kDefaultMinPasses;  ///< with relError: passes before the error estimate is trusted (≥ 2)
  int passLimit = 1 << 16;      ///< with relError only: give up after this many passes
  /// Light leaving the translucent objects onto the opaque receivers (one bounce, Lambertian
  /// receivers). Only when the GPU renders it too (VPLs), so that like is compared with like.
  bool emergentLight = false;
  int emitterPoints = kDefaultEmitterPoints;  ///< with emergentLight: emitter points per translucent object and pass (≥ 1)
  /// The triangles the renderer draws for field objects at timeS (GpuDualContouring::readBack;
  /// app::drawnFieldMeshes), so that the reference integrates over the surface the image shows. A
  /// field object not in it is meshed on the CPU (geometry::meshOnCpu, OpenVDB volumeToMesh on the
  /// same lattice), whose vertices differ from the GPU's by up to a lattice cell: at a sharp rim
  /// that moves silhouettes and creases by a pixel (docs/reference.md).
  FieldMeshes fieldMeshes;
};

/// The statistic the stopping rule and the metadata use, over the pixels whose camera ray hits a
/// translucent object: ε = √(mean_p Σ_c se_{p,c}²) / √(mean_p Σ_c L_{p,c}²), the relative RMS of the
/// per-pixel standard errors of the mean (se² = sample variance of the pass estimates / passes).
/// It predicts the relative RMSE of the reference itself in the bench's colour-band metric.
inline constexpr const char* kReferenceErrorStatistic = "relative RMS standard error over translucent pixels";
/// ReferenceResult::emergentRelError, reported (not a stopping rule).
inline constexpr const char* kEmergentErrorStatistic =
    "relative RMS standard error of the emergent term over receiver pixels with emergent light";

/// The estimator's distribution is skewed by the near-field peak of S_d (r ≲ 1/σ_t'): with fewer
/// than about one point per pass within 1/σ_t' of x_o, passes usually miss the peak and both the
/// mean and the standard error come out low. nearFieldPoints = M π / (A σ_t'²) (σ_t' of the band
/// with the largest one, A the object's area in mm²) is that expected count on a flat surface.
inline constexpr double kNearFieldTarget = 4.0;
inline constexpr int kMinAutoPoints = 4096;
inline constexpr int kMaxAutoPoints = 1 << 22;

struct ReferenceResult {
  gpu::Image radiance;       ///< linear RGB, alpha 1: the mean of the passes
  /// Per pixel and band, the standard error of that mean (0 after one pass); alpha 1 on the pixels
  /// whose camera ray hits a translucent object (the bench's object pixels), 0 elsewhere.
  gpu::Image standardError;
  int passes = 0;
  int pointsPerPass = 0;     ///< M (the largest over objects when chosen per object)
  double nearFieldPoints = 0.0;  ///< the smallest over translucent objects (0 without any)
  double relError = 0.0;     ///< ε above after the last pass (infinity after one pass with translucent pixels)
  int translucentPixels = 0;
  /// The emergent term alone (emergentLight), mean over passes, linear RGB; alpha 1 on the
  /// receiver pixels (camera ray hits an opaque surface), 0 elsewhere. Empty (0×0) when off.
  gpu::Image emergent;
  int emitterPoints = 0;      ///< emitter points per object and pass (0: emergent light off)
  int emergentPixels = 0;     ///< receiver pixels with emergent light (mean > 0 in some band)
  /// ε of kReferenceErrorStatistic over the emergentPixels with the emergent term's mean as the
  /// scale: √(mean_p Σ_c se_{p,c}²) / √(mean_p Σ_c Ē_{p,c}²) (0 without such pixels).
  double emergentRelError = 0.0;
  std::size_t triangles = 0;  ///< in the Embree scene
  double seconds = 0.0;       ///< wall time of the integration (set-up included)
};

/// Called after every pass with (passes done, ε); return false to stop early.
using ReferenceProgress = std::function<bool(int passes, double relError)>;

/// Renders `scene` (lights as loaded: environment lights included, flame lights moved to timeS)
/// with `render`'s size, camera aspect, sss.model, method, specular, shadows, ambient and background.
/// Throws std::invalid_argument (one line) on bad settings: neither stop given, maxPasses < 0,
/// relError < 0 or not finite, pointsPerPass < 0, emitterPoints < 1 with emergentLight, size < 1; std::runtime_error when a mesh or the
/// environment map cannot be read.
ReferenceResult renderReference(const Scene& scene, const RenderSettings& render, const ReferenceSettings& settings,
                                const ReferenceProgress& progress = {});

}  // namespace tallow::sss
