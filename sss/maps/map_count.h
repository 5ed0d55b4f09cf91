#pragma once
// sss.maps=auto: K, the number of scattered radiosity maps, from their measured coverage (issue 17,
// point 4; the paper's Fig. 13: "the first 7 maps cover most of the surface, while the following 4
// cover small details", and §5: 16 for simple shapes, 31 for the dragon).
//
// The maps' directions are a Halton sequence, so the maps of a smaller K are the first maps of a
// larger one. The GPU records, for every visible camera pixel of a translucent object and for every
// VPL, the first map that sees it, and for the pixels also the second map that sees them within 60°
// of their normal (shaders/maps/coverage_counts.glsl, coverage_histogram.comp). A histogram of those
// indices says at once how many points every K' ≤ K would leave unseen: a hole (Algorithm 1 gives
// B = 0: a dark spot, a dark VPL), or fewer than two facing maps (B blurred over 1/cos θ of surface:
// on the marble bunny, the 8th map is the first to face 412 of its 2500 pixels, and dropping it
// takes the converged error from 7.4% to 10.4%; with one facing map a pixel takes that map's blur
// and bias nearly alone: the animated candle's lower-wall silhouette read 10% bright at K = 8, a
// firefly the reference lacks; docs/radiosity-maps.md). The renderer reads the counts back without
// waiting (a fence, a frame or more later: sss/maps/map_coverage_probe.h) and MapCountChooser picks
// the K of the next frames, per histogram h with its tolerance τ_h (holes: kAutoMapsHoleTolerance, grazing:
// kAutoMapsGrazingTolerance):
//   - shrink to the smallest K' that leaves at most τ_h more of h's points unseen than the fewest
//     measured so far at this K or a larger one (in every histogram). Against that floor, not the
//     current K, so that K does not creep down a map at a time, each losing τ_h again;
//   - grow (double, at most kAutoMapsMax) while more than m·τ_h of a histogram's points are unseen
//     and no larger K is known to leave about as many unseen (what no direction reaches: the inside
//     of a closed concavity), so that K does not swing between two values.
// m = kAutoMapsHysteresis: a K chosen for leaving at most τ more unseen grows again only past m·τ,
// so a playing preset keeps its K while its coverage wanders a little from frame to frame (issue
// 38: with m = 1 the blob at 8 fps went 16, 12, …, 12, 24, 12 as the grazing share at K = 12
// touched 2.1% for one frame, and each change restarts the maps and reallocates them). The band is
// on growth only: a tighter shrink (τ / m) took the bunny from 12 maps to 14 for 1% of its pixels.
// A change of K in a frame where nothing moved keeps the first min(K, K') maps and starts only the
// new ones (MapsUpdate::Resize; with sss.history=0 it restarts them all, as the paper does).
#include <array>
#include <cstdint>
#include <map>
#include <optional>

#include "gpu/glsl_shared.h"

namespace tallow::glsl {
#include "shaders/maps/coverage_counts.glsl"
}  // namespace tallow::glsl

namespace tallow::sss {

constexpr int kAutoMapsMax = glsl::COVERAGE_MAX_MAPS;
constexpr int kAutoMapsFirst = 16;  ///< K of the first frames, before any coverage is known (the paper's §5)
/// The share of the pixels or VPLs that may be left with no map (holes), and with fewer than two maps
/// facing them.
constexpr double kAutoMapsHoleTolerance = 1e-3;
constexpr double kAutoMapsGrazingTolerance = 0.02;
/// Grow only above m·τ (shrinking keeps τ): the band a wandering coverage stays in.
constexpr double kAutoMapsHysteresis = 1.5;

/// One histogram: first[k] points first seen by map k (k < maps), `unseen` by none.
struct CoverageHistogram {
  std::array<std::uint64_t, kAutoMapsMax> first{};
  std::uint64_t unseen = 0;
  std::uint64_t total(int maps) const;
  /// Points that none of the first `k` maps sees, when `maps` maps were drawn (k ≤ maps).
  std::uint64_t unseenWith(int k, int maps) const;
};

/// What one frame measured: its K and the histograms of shaders/maps/coverage_counts.glsl (the
/// VPLs' only when the VPL pass ran; an empty histogram is not counted).
struct MapCoverageCounts {
  int maps = 0;
  CoverageHistogram camera;        ///< the pixels, by the first map that sees them
  CoverageHistogram cameraFacing;  ///< the pixels, by the second map within 60° of their normal
  std::optional<CoverageHistogram> vpls;
};

class MapCountChooser {
 public:
  int k() const { return k_; }
  /// Takes a frame's counts; counts made with another K than the current one (read back after a
  /// change) are ignored. Returns true when K changed.
  bool update(const MapCoverageCounts& counts);

 private:
  int k_ = kAutoMapsFirst;
  /// The unseen share last measured at each K, per histogram (camera, camera facing, VPLs;
  /// negative: not measured).
  std::map<int, std::array<double, 3>> unseenAt_;
};

}  // namespace tallow::sss
