#pragma once
// FLOPs of one sample of the scattered-radiosity gather (shaders/maps/gather.glsl), counted by
// running the shared lines it calls per sample (shaders/maps/estimator.glsl: sssDrawSharedSample,
// sssPointOnTexel, sssRadiosityTerm with the BSSRDF of shaders/bssrdf/) with a counting scalar
// (counted_real.h). The gather's own glue around them (the G-buffer look-up, normalising the
// looked-up normal, the projected-area division) is GLSL only and not counted, so the count is a
// lower bound on the sample's arithmetic by a few operations.
#include <cstdint>

#include "sss/bssrdf/bssrdf.h"
#include "sss/bssrdf/material.h"

namespace tallow::flops {

struct GatherFlops {
  int samples = 0;  ///< samples counted, each shared by the three bands (every one reaches S_d)
  /// Mean FLOPs (add + mul + div + special) of one sample for the three bands (one draw, one x_i,
  /// three terms: issue 17), and its extremes over the samples.
  double flopsPerSharedSample = 0.0;
  std::uint64_t flopsSharedMin = 0, flopsSharedMax = 0;
  /// flopsPerSharedSample / 3: per sample and band, the unit `probe maps` counts evaluations in.
  double flopsMean = 0.0;
  double addMean = 0.0, mulMean = 0.0, divMean = 0.0, specialMean = 0.0, otherMean = 0.0;
  /// The counted evaluation's value equals the float instantiation's (sss::evaluateRadiosityTerm
  /// in float) for every sample: the counted lines are the shader's, computed in float.
  double maxValueDifference = 0.0;
};

/// Samples of a directional light at normal incidence on a plane of `material` (every band), the
/// sample's x_i on the plane, so that every sample is lit and reaches the BSSRDF: the gather's full
/// path, which probe maps' evaluations per second count for every sample. `samplesPerBand` ≥ 1: the
/// N of the gather, whose samples the three bands share.
GatherFlops countGatherFlops(const sss::Material& material, sss::BssrdfModel model, int samplesPerBand);

}  // namespace tallow::flops
