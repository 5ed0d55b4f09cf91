#pragma once
// Volumetric Monte Carlo reference for a planar medium: a pencil beam on a half-space or a slab,
// photon random walk with Henyey–Greenstein scattering and exact Fresnel boundaries. It is the
// ground truth for *model* error of the BSSRDFs, so it shares no code with them (its Fresnel and
// phase-function sampling are its own). Method and validation: docs/planar-mc.md.
//
// Frame: the medium is z < 0 (half-space) or −d < z < 0 (slab, air on both sides); the beam hits
// the origin from outside (z > 0) travelling along (sin θ, 0, −cos θ), i.e. from −x toward +x for
// θ > 0. Lengths in mm, coefficients in mm⁻¹; exitance tallies are per unit area per unit
// incident power [mm⁻²].
#include <cstdint>
#include <limits>
#include <vector>

namespace tallow::sss {

struct PlanarMcSetup {
  double sigma_a = 0.0;  ///< absorption coefficient [mm⁻¹], ≥ 0
  double sigma_s = 1.0;  ///< scattering coefficient [mm⁻¹], ≥ 0, σ_a + σ_s > 0
  double g = 0.0;        ///< Henyey–Greenstein mean cosine, |g| < 1
  double eta = 1.0;      ///< relative index of refraction (inside / outside), > 0
  double thicknessMm = std::numeric_limits<double>::infinity();  ///< slab thickness d; ∞: half-space
  double thetaDeg = 0.0;  ///< angle of incidence from the normal, in (−90°, 90°)

  std::uint64_t photons = 100000;  ///< photon packets, ≥ 1
  std::uint64_t seed = 1;          ///< results are a function of (setup, seed) only, any thread count
  int threads = 0;                 ///< worker threads; 0: std::thread::hardware_concurrency()

  /// Exitance along the x axis: xBins bins over [xMinMm, xMaxMm) of a strip |y| < stripWidthMm/2.
  double xMinMm = -1.0, xMaxMm = 1.0;
  int xBins = 0;  ///< 0: no x profile
  double stripWidthMm = 0.1;
  /// Exitance map over [−mapHalfWidthMm, mapHalfWidthMm)², mapBins × mapBins.
  double mapHalfWidthMm = 1.0;
  int mapBins = 0;  ///< 0: no map
  /// Radial exitance R_d(r): rBins annuli over [0, rMaxMm), about the point of incidence.
  double rMaxMm = 1.0;
  int rBins = 0;  ///< 0: no radial profile

  /// Safeguard: a path is cut (and counted, with its weight) after this length in mean free paths
  /// 1/(σ_a + σ_s). Only non- or barely absorbing media reach it.
  double maxPathLengthMfp = 1e6;
};

/// A Monte Carlo estimate: the mean over photons and its standard error (per-photon sample
/// variance / N, square-rooted).
struct McEstimate {
  double mean = 0.0;
  double stdErr = 0.0;
};

/// A binned tally with the standard error of each bin.
struct McProfile {
  std::vector<double> mean;
  std::vector<double> stdErr;
};

/// Fractions of the incident power unless said otherwise.
struct PlanarMcResult {
  std::uint64_t photons = 0;
  /// Fresnel reflection of the beam at the entry point (exact, not sampled); not part of R_d.
  double specularReflectance = 0.0;
  /// Everything that leaves through z = 0 after entering (all scattering orders, MCML's R_d).
  McEstimate diffuseReflectance;
  /// Everything that leaves through z = −d, unscattered light included (MCML's T_t); 0 for the
  /// half-space.
  McEstimate transmittance;
  McEstimate absorbed;
  /// Parts of the above by scattering order, for exact checks and for models without single
  /// scattering: R_d after exactly one scattering event; light leaving through z = 0 or z = −d
  /// without any.
  McEstimate singleScatterReflectance;
  McEstimate unscatteredReflectance;
  McEstimate unscatteredTransmittance;
  /// Russian roulette's weight created minus weight destroyed, per photon; its expectation is 0.
  /// Bookkeeping closes exactly: specular + R_d + T + absorbed + truncatedWeight − rouletteNet = 1.
  McEstimate rouletteNet;
  std::uint64_t truncatedPaths = 0;  ///< paths cut at maxPathLengthMfp
  double truncatedWeight = 0.0;      ///< their remaining weight per incident photon (lost)
  std::uint64_t interactions = 0;    ///< scattering events simulated (for photon-step rates)

  /// Exitance at z = 0 [mm⁻²] (all orders, as R_d), bin i centred at
  /// xMinMm + (i + ½)(xMaxMm − xMinMm)/xBins.
  McProfile xProfile;
  McProfile xProfileSingle;  ///< the single-scattering part of xProfile
  /// Row-major, map[iy·mapBins + ix], bin centres −h + (i + ½)·2h/mapBins for x and y.
  McProfile map;
  /// Bin i over the annulus [i, i+1)·rMaxMm/rBins.
  McProfile radial;
};

/// Throws std::invalid_argument (one line naming the field) for an unusable setup.
void validatePlanarMcSetup(const PlanarMcSetup& setup);

/// Runs the simulation (validates first). Deterministic: equal setups and seeds give bitwise
/// equal results for every thread count.
PlanarMcResult simulatePlanarMedium(const PlanarMcSetup& setup);

/// Centre of bin i of `bins` equal bins over [lo, hi).
inline double planarMcBinCentre(double lo, double hi, int bins, int i) {
  return lo + (i + 0.5) * (hi - lo) / bins;
}

/// The reference's own optics, exposed for tests (not for reuse by the models: the reference
/// stays independent of them).
namespace planar_mc {

/// Unpolarised Fresnel reflectance for light arriving at cosine cosIncident ∈ [0, 1] from the
/// medium of index nIncident onto index nTransmitted; 1 beyond the critical angle.
double fresnelReflectance(double cosIncident, double nIncident, double nTransmitted);

/// Cosine of the scattering angle drawn from Henyey–Greenstein with mean cosine g (|g| < 1) by
/// exact inversion of its CDF, u uniform in [0, 1); written without 1/g so g → 0 is exact.
double sampleHenyeyGreensteinCos(double g, double u);

}  // namespace planar_mc

}  // namespace tallow::sss
