// Issue 39, point 5: on a history reuse the history passes (maps/history.comp, history_merge.comp)
// visit only the map texels with a surface in this or the last frame's G-buffer, listed by
// maps/covered_texels.comp and dispatched indirectly. The pictures must be those of the passes over
// every texel, bit for bit, and the maps pass must invoke fewer compute shaders.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "gpu/gl_limits.h"
#include "sss/maps/radiosity_maps.h"
#include "support/render_support.h"

namespace tallow {
namespace {

struct Played {
  gpu::Image last;
  std::uint64_t mapsCompute = 0;  ///< the maps pass's compute invocations in the last frame
};

/// The preset played at 8 fps for `frames` frames from `start`, then held still for `still` frames
/// (the kept history fades: maps/history_fade.comp), the history passes over the listed texels or
/// over every texel.
Played play(const std::string& preset, const std::vector<std::string>& sets, double start, int frames, int still,
            bool compacted) {
  sss::RadiosityMaps::allowCompactedHistory(compacted);
  test::PresetSession s(preset, sets);
  Played out;
  for (int f = 0; f < frames + still; ++f) {
    sss::FrameTimings t;
    out.last = s.render(start + std::min(f, frames - 1) / 8.0, &t);
    for (const gpu::PassTiming& p : t.passes)
      if (p.name == "sss.maps" && p.counts) out.mapsCompute = p.counts->compute;
  }
  sss::RadiosityMaps::allowCompactedHistory(true);
  return out;
}

void expectSamePictures(const std::string& preset, const std::vector<std::string>& sets, double start, int still = 0) {
  const Played listed = play(preset, sets, start, 5, still, true), every = play(preset, sets, start, 5, still, false);
  ASSERT_EQ(listed.last.pixels.size(), every.last.pixels.size());
  double lit = 0.0;
  for (std::size_t i = 0; i < listed.last.pixels.size(); ++i) {
    const glm::vec4 a = listed.last.pixels[i], b = every.last.pixels[i];
    lit += a.r + a.g + a.b;
    ASSERT_TRUE(a == b) << preset << ": pixel " << i << ": " << a.r << " vs " << b.r;
  }
  EXPECT_GT(lit, 0.0);
  if (gpu::glLimits().pipelineStatistics) {
    std::printf("[ history ] %s: maps pass compute invocations %llu over the listed texels, %llu over every texel\n",
                preset.c_str(), static_cast<unsigned long long>(listed.mapsCompute),
                static_cast<unsigned long long>(every.mapsCompute));
    EXPECT_LT(listed.mapsCompute, every.mapsCompute) << preset;
  }
}

TEST(CoveredHistory, TheBlobPlayingIsDrawnAsWithPassesOverEveryTexel) {
  expectSamePictures("blob", {"render.width=96", "render.height=54", "sss.maps=6", "sss.map_size=128"}, 1.0);
}

// A still after the motion: the kept frames fade over the texels the last merge listed.
TEST(CoveredHistory, TheBlobsStillAfterMotionFadesAsWithPassesOverEveryTexel) {
  expectSamePictures("blob", {"render.width=96", "render.height=54", "sss.maps=6", "sss.map_size=128", "sss.frames=8"},
                     1.0, 3);
}

TEST(CoveredHistory, TheMeltingCandleIsDrawnAsWithPassesOverEveryTexel) {
  expectSamePictures("candle",
                     {"render.width=96", "render.height=54", "field.res=48", "vpl.count=0", "sss.maps=6",
                      "sss.map_size=128", "flame.flicker=0"},
                     12.0);
}

}  // namespace
}  // namespace tallow
