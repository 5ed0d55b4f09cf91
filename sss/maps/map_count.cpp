#include "sss/maps/map_count.h"

#include <algorithm>
#include <vector>

namespace tallow::sss {

std::uint64_t CoverageHistogram::total(int maps) const { return unseenWith(0, maps); }

std::uint64_t CoverageHistogram::unseenWith(int k, int maps) const {
  std::uint64_t n = unseen;
  for (int i = std::max(k, 0); i < std::min(maps, kAutoMapsMax); ++i) n += first[static_cast<std::size_t>(i)];
  return n;
}

namespace {

double unseenShare(const CoverageHistogram& h, int maps) {
  const std::uint64_t total = h.total(maps);
  return total ? static_cast<double>(h.unseen) / static_cast<double>(total) : 0.0;
}

/// The smallest K' ≤ maps whose maps leave at most `allowedShare` of the section unseen (maps if none).
int smallestSufficient(const CoverageHistogram& h, int maps, double allowedShare) {
  const double allowed = allowedShare * static_cast<double>(h.total(maps));
  for (int k = 1; k < maps; ++k)
    if (static_cast<double>(h.unseenWith(k, maps)) <= allowed) return k;
  return maps;
}

}  // namespace

bool MapCountChooser::update(const MapCoverageCounts& counts) {
  if (counts.maps != k_) return false;
  const std::array<const CoverageHistogram*, 3> histograms{&counts.camera, &counts.cameraFacing,
                                                           counts.vpls ? &*counts.vpls : nullptr};
  const std::array<double, 3> tolerance{kAutoMapsHoleTolerance, kAutoMapsGrazingTolerance, kAutoMapsHoleTolerance};
  std::array<double, 3> share{-1.0, -1.0, -1.0};
  for (std::size_t h = 0; h < share.size(); ++h)
    if (histograms[h] && histograms[h]->total(k_) > 0) share[h] = unseenShare(*histograms[h], k_);
  if (share[0] < 0.0 && share[2] < 0.0) return false;  // nothing translucent was seen: nothing to go by
  unseenAt_[k_] = share;
  const int before = k_;
  int sufficient = 1;
  bool grow = false;
  for (std::size_t h = 0; h < share.size(); ++h) {
    if (share[h] < 0.0) continue;
    double floor = share[h];
    bool unseenAnyway = false;  // a larger K measured left about as much unseen
    for (auto it = unseenAt_.upper_bound(k_); it != unseenAt_.end(); ++it) {
      if (it->second[h] < 0.0) continue;
      floor = std::min(floor, it->second[h]);
      unseenAnyway = unseenAnyway || it->second[h] >= share[h] - tolerance[h];
    }
    grow = grow || (share[h] > kAutoMapsHysteresis * tolerance[h] && !unseenAnyway);
    sufficient = std::max(sufficient, smallestSufficient(*histograms[h], k_, floor + tolerance[h]));
  }
  if (grow && k_ < kAutoMapsMax) {
    k_ = std::min(2 * k_, kAutoMapsMax);
    return true;
  }
  k_ = sufficient;
  return k_ != before;
}

}  // namespace tallow::sss
