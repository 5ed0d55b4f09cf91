#pragma once
// FLOPs of the scattered-radiosity gather (shaders/maps/gather_loop.glsl, the loops the GPU runs),
// counted by running those very lines with a counting scalar (counted_real.h): the directional
// light's loop and the point light's, each per sample and per texel. Only the G-buffer look-ups
// (texture fetches on the GPU) are left out.
#include <cstdint>
#include <vector>

#include "app/bench_report/counted_real.h"
#include "sss/bssrdf/bssrdf.h"
#include "sss/bssrdf/material.h"

namespace tallow::flops {

/// The counts so far at each G-buffer look-up of the counted gather (per thread): the loop's
/// samples lie between them.
std::vector<OpCounts>& marks();

/// One light's loop.
struct LoopFlops {
  int samples = 0;  ///< samples counted between look-ups, each shared by the three bands
  /// Mean FLOPs (add + mul + div + special) of one sample for the three bands (one draw, one x_i,
  /// the area ratio, three terms: issue 17), and its extremes over the samples.
  double flopsPerSharedSample = 0.0;
  std::uint64_t flopsSharedMin = 0, flopsSharedMax = 0;
  /// flopsPerSharedSample / 3: per sample and band, the unit `probe maps` counts evaluations in.
  double flopsMean = 0.0;
  double addMean = 0.0, mulMean = 0.0, divMean = 0.0, specialMean = 0.0, otherMean = 0.0;
  /// FLOPs per texel outside the samples (coefficients, the basis, the sums' scaling).
  double flopsPerTexel = 0.0;
};

struct GatherFlops {
  LoopFlops directional;  ///< a directional light at normal incidence on a plane
  LoopFlops point;        ///< a point light at the centre of a spherical cup (the candle's flame)
  /// The counted gather's value equals the float instantiation's for both loops: the counted lines
  /// are the shader's, computed in float.
  double maxValueDifference = 0.0;
};

/// The gather of one texel of `material` with each kind of light alone, N = samplesPerBand ≥ 2
/// samples (shared by the bands), sss.* at their defaults; every sample is lit and reaches the
/// BSSRDF: the gather's full path, which probe maps' evaluations per second count for every sample.
GatherFlops countGatherFlops(const sss::Material& material, sss::BssrdfModel model, int samplesPerBand);

}  // namespace tallow::flops
