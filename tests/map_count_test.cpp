// sss.maps=auto's choice of K from coverage counts (sss/maps/map_count.h). The expected K of each
// case is worked out by hand from the histogram it builds, or (the random scenes) by brute force:
// every K' ≤ 32 tried against the same model of which maps see which points.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "sss/maps/map_count.h"

namespace tallow {
namespace {

using sss::CoverageHistogram;
using sss::MapCountChooser;
using sss::MapCoverageCounts;

CoverageHistogram histogram(std::initializer_list<std::uint64_t> first, std::uint64_t unseen) {
  CoverageHistogram h;
  std::size_t i = 0;
  for (std::uint64_t n : first) h.first[i++] = n;
  h.unseen = unseen;
  return h;
}

MapCoverageCounts counts(int maps, const CoverageHistogram& camera) {
  MapCoverageCounts c;
  c.maps = maps;
  c.camera = camera;
  return c;
}

TEST(MapCount, HistogramCountsWhatFewerMapsLeaveUnseen) {
  const CoverageHistogram h = histogram({500, 300, 0, 150, 50}, 7);
  EXPECT_EQ(h.total(5), 1007u);
  EXPECT_EQ(h.unseenWith(5, 5), 7u);
  EXPECT_EQ(h.unseenWith(4, 5), 57u);
  EXPECT_EQ(h.unseenWith(1, 5), 507u);
  EXPECT_EQ(h.unseenWith(0, 5), 1007u);
  EXPECT_EQ(h.unseenWith(3, 4), 157u) << "bins at or past `maps` are not counted";
}

TEST(MapCount, StartsAtSixteenAndShrinksToTheFewestMapsThatSeeAllButTheTolerance) {
  MapCountChooser c;
  EXPECT_EQ(c.k(), 16);
  // 10000 pixels; without map 6 the 10 pixels only it sees would be lost (0.1% = 10: allowed),
  // without map 5 also its 5 more (15 > 10).
  CoverageHistogram h;
  h.first[0] = 6000;
  h.first[1] = 2000;
  h.first[2] = 1000;
  h.first[3] = 900;
  h.first[4] = 85;
  h.first[5] = 5;
  h.first[6] = 10;
  ASSERT_EQ(h.total(16), 10000u);
  EXPECT_TRUE(c.update(counts(16, h)));
  EXPECT_EQ(c.k(), 6);
}

TEST(MapCount, IgnoresCountsMadeWithAnotherK) {
  MapCountChooser c;
  EXPECT_FALSE(c.update(counts(8, histogram({100}, 0))));
  EXPECT_EQ(c.k(), 16);
  EXPECT_FALSE(c.update(counts(16, CoverageHistogram{}))) << "nothing translucent seen: nothing to go by";
  EXPECT_EQ(c.k(), 16);
}

TEST(MapCount, GrowsWhileHolesRemainUpToThirtyTwo) {
  MapCountChooser c;
  CoverageHistogram h;
  h.first[0] = 1000;
  h.unseen = 20;  // 2% unseen
  EXPECT_TRUE(c.update(counts(16, h)));
  EXPECT_EQ(c.k(), 32);
  // At 32 the same holes (nothing a larger K can do): shrink to what sees the rest.
  EXPECT_TRUE(c.update(counts(32, h)));
  EXPECT_EQ(c.k(), 1);
  // Back at 1 the holes are as large as at 32: no growth again (no swinging between 1 and 32).
  EXPECT_FALSE(c.update(counts(1, h)));
  EXPECT_EQ(c.k(), 1);
}

TEST(MapCount, TheVplsKeepTheMapsOnlyTheySee) {
  MapCountChooser c;
  MapCoverageCounts m = counts(16, histogram({1000}, 0));
  CoverageHistogram v;
  v.first[0] = 70;
  v.first[9] = 1;  // one VPL of 71 seen first by map 9
  m.vpls = v;
  EXPECT_TRUE(c.update(m));
  EXPECT_EQ(c.k(), 10);
}

TEST(MapCount, PixelsThatOnlyGrazingMapsSeeCountWithTheirOwnTolerance) {
  // 10000 pixels, every one seen by map 0, so holes ask for one map. Facing them within 60°: at 16
  // maps 8% of them have none (over the 2% tolerance: grow to 32, not tried yet); at 32, 7.5%.
  MapCountChooser c;
  MapCoverageCounts at16 = counts(16, histogram({10000}, 0));
  at16.cameraFacing.first[0] = 8688;
  at16.cameraFacing.first[7] = 412;
  at16.cameraFacing.first[8] = 100;
  at16.cameraFacing.unseen = 800;
  EXPECT_TRUE(c.update(at16));
  EXPECT_EQ(c.k(), 32);
  MapCoverageCounts at32 = counts(32, histogram({10000}, 0));
  at32.cameraFacing = at16.cameraFacing;
  at32.cameraFacing.first[20] = 50;
  at32.cameraFacing.unseen = 750;
  // Allowed unseen: 7.5% + 2% = 950 pixels. Without maps 8-31: 750 + 150 = 900 (fine); without
  // map 7 too: 1312. K = 8.
  EXPECT_TRUE(c.update(at32));
  EXPECT_EQ(c.k(), 8);
  // At 8, 9% have no facing map, but 32 maps left 7.5%: within the tolerance, no growth; settled.
  MapCoverageCounts at8 = counts(8, histogram({10000}, 0));
  at8.cameraFacing.first[0] = 8688;
  at8.cameraFacing.first[7] = 412;
  at8.cameraFacing.unseen = 900;
  EXPECT_FALSE(c.update(at8));
  EXPECT_EQ(c.k(), 8);
}

TEST(MapCount, ACoverageThatWandersWithinTheBandKeepsK) {
  // 10000 pixels all seen by map 0; facing them, 16 maps leave none with fewer than two, 12 maps
  // 1.2%, 2.1% or 3.5% (a playing blob's grazing share from frame to frame). Within m·τ = 3%: K
  // stays; beyond it K doubles. Without the band (grow above τ = 2%) the 2.1% frame doubled K.
  const auto at12 = [](std::uint64_t unseenFacing) {
    MapCoverageCounts m = counts(16, histogram({10000}, 0));
    m.cameraFacing.first[0] = 10000 - unseenFacing - 201;
    m.cameraFacing.first[11] = 201;  // the 12th map is the second facing one of 2.01% of them
    m.cameraFacing.unseen = unseenFacing;
    return m;
  };
  MapCountChooser c;
  EXPECT_TRUE(c.update(at12(0)));  // 16 maps face every pixel twice
  ASSERT_EQ(c.k(), 12) << "without map 12: 2.01% unseen, over 0% + τ (2%) by a pixel";
  for (std::uint64_t unseen : {210u, 120u, 210u}) {
    MapCoverageCounts m = at12(unseen);
    m.maps = 12;
    EXPECT_FALSE(c.update(m)) << unseen << " of 10000";
    EXPECT_EQ(c.k(), 12);
  }
  MapCoverageCounts far = at12(350);
  far.maps = 12;
  EXPECT_TRUE(c.update(far));
  EXPECT_EQ(c.k(), 24) << "3.5% > 1.5 x 2%, and no larger K measured that much";
}

/// A scene as the chooser sees it: per point, the set of the 32 Halton maps that see it (a bit
/// mask); the counts a K gives follow from it, as Algorithm 1 makes them.
struct CoverageModel {
  std::vector<std::uint32_t> seenBy;

  CoverageHistogram at(int k) const {
    CoverageHistogram h;
    for (std::uint32_t mask : seenBy) {
      const std::uint32_t visible = k >= 32 ? mask : mask & ((1u << k) - 1u);
      if (visible == 0) ++h.unseen;
      else ++h.first[static_cast<std::size_t>(__builtin_ctz(visible))];
    }
    return h;
  }
  double unseenShare(int k) const {
    return static_cast<double>(at(k).unseen) / static_cast<double>(seenBy.size());
  }
};

CoverageModel randomModel(std::mt19937& rng) {
  // Each point is seen by each map with a probability of its own (an open face: high; a crease:
  // low; a closed cavity: zero), as on a real object.
  CoverageModel m;
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int points = 2000 + static_cast<int>(u(rng) * 20000);
  const double cavity = u(rng) < 0.3 ? 0.01 * u(rng) : 0.0;
  const double openness = 0.1 + 3.0 * u(rng);  // small: most points seen by most maps
  for (int i = 0; i < points; ++i) {
    const double p = u(rng) < cavity ? 0.0 : std::pow(u(rng), openness);
    std::uint32_t mask = 0;
    for (int k = 0; k < 32; ++k)
      if (u(rng) < p) mask |= 1u << k;
    m.seenBy.push_back(mask);
  }
  return m;
}

TEST(MapCount, RandomScenesSettleOnAKThatSeesWhatThirtyTwoSeeWithinTheTolerance) {
  std::mt19937 rng(20261202u);
  int grew = 0, shrank = 0;
  for (int scene = 0; scene < 200; ++scene) {
    const CoverageModel m = randomModel(rng);
    MapCountChooser c;
    std::vector<int> ks;
    for (int frame = 0; frame < 12; ++frame) {
      ks.push_back(c.k());
      c.update(counts(c.k(), m.at(c.k())));
    }
    // Settled: the last five frames use one K.
    const int k = ks.back();
    grew += std::count(ks.begin(), ks.end(), 32) > 0 ? 1 : 0;
    shrank += k < 16 ? 1 : 0;
    std::string history;
    for (int x : ks) history += std::to_string(x) + " ";
    for (std::size_t i = ks.size() - 5; i < ks.size(); ++i) ASSERT_EQ(ks[i], k) << "scene " << scene << ": K " << history;
    // Against the model: the chosen K leaves unseen at most the tolerance more than 32 maps do
    // (when those leave more than the tolerance: holes), or than m times the tolerance itself
    // (growth stops there: kAutoMapsHysteresis)…
    const double tau = sss::kAutoMapsHoleTolerance;
    EXPECT_LE(m.unseenShare(k), std::max(m.unseenShare(32), sss::kAutoMapsHysteresis * tau) + tau + 1e-12)
        << "scene " << scene << ", K " << k;
    // … and it is the fewest maps that do so: every smaller K leaves more than the tolerance
    // unseen beyond the fewest unseen measured at K or at a larger K the chooser tried.
    double floor = 1.0;
    for (int tried : ks)
      if (tried >= k) floor = std::min(floor, m.unseenShare(tried));
    for (int j = 1; j < k; ++j)
      EXPECT_GT(m.unseenShare(j), floor + tau - 1e-12)
          << "scene " << scene << ": K " << history << "where " << j << " maps see as much";
  }
  // Both rules were exercised (of 200 scenes).
  EXPECT_GT(grew, 10);
  EXPECT_GT(shrank, 10);
}

}  // namespace
}  // namespace tallow
