// sss.history's per-texel rule (shaders/maps/history.glsl, compiled as C++ by sss/maps/map_history.h)
// and its tolerances: keep a texel's sum where its surface point and normal still hold, trimmed so
// that with this frame it holds at most `history` frames; reset it elsewhere.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "sss/maps/map_history.h"
#include "sss/maps/radiosity_estimator.h"

namespace tallow {
namespace {

using sss::history_glsl::sssHistoryScale;

constexpr float kMove = 1e-3f;                     // maxMove [m]
const float kMinCos = std::cos(25.0f * 3.14159265f / 180.0f);

float scale(glm::vec3 oldP, float oldSlot, glm::vec3 oldN, glm::vec3 newP, float newSlot, glm::vec3 newN, float frames,
            float history) {
  return sssHistoryScale(oldP, oldSlot, oldN, newP, newSlot, newN, frames, history, kMove, kMinCos);
}

TEST(MapHistory, AHeldTexelKeepsAtMostHistoryMinusOneFrames) {
  const glm::vec3 p(0.1f, 0.2f, 0.3f), n(0.0f, 0.0f, 1.0f);
  EXPECT_FLOAT_EQ(scale(p, 1, n, p, 1, n, 2, 8), 1.0f) << "2 frames of 8: kept whole";
  EXPECT_FLOAT_EQ(scale(p, 1, n, p, 1, n, 7, 8), 1.0f) << "7 = history − 1: kept whole";
  EXPECT_FLOAT_EQ(scale(p, 1, n, p, 1, n, 20, 8), 7.0f / 20.0f) << "trimmed to 7 frames";
  EXPECT_FLOAT_EQ(scale(p, 1, n, p, 1, n, 20, 1), 0.0f) << "history 1: only this frame";
  EXPECT_FLOAT_EQ(scale(p, 1, n, p, 1, n, 20, 0), 0.0f) << "history 0: reset";
  EXPECT_FLOAT_EQ(scale(p, 1, n, p, 1, n, 0, 8), 0.0f) << "nothing accumulated";
  // Whatever the count, the kept frames plus this one never exceed `history`.
  std::mt19937 rng(7);
  for (int i = 0; i < 1000; ++i) {
    const float frames = static_cast<float>(std::uniform_int_distribution<int>(1, 5000)(rng));
    const float history = static_cast<float>(std::uniform_int_distribution<int>(1, 64)(rng));
    const float kept = frames * scale(p, 1, n, p, 1, n, frames, history);
    EXPECT_LE(kept + 1.0f, history * (1.0f + 1e-6f)) << frames << " frames, history " << history;
    EXPECT_GE(kept + 1.0f, std::min(frames + 1.0f, history) * (1.0f - 1e-6f)) << "keeps as much as it may";
  }
}

TEST(MapHistory, ATexelWhoseSurfaceMovedTurnedOrChangedIsReset) {
  const glm::vec3 p(0.1f, 0.2f, 0.3f), n(0.0f, 0.0f, 1.0f);
  const glm::vec3 along(0.6f, 0.0f, 0.8f);  // unit
  EXPECT_GT(scale(p, 1, n, p + 0.99f * kMove * along, 1, n, 4, 8), 0.0f);
  EXPECT_EQ(scale(p, 1, n, p + 1.01f * kMove * along, 1, n, 4, 8), 0.0f) << "moved beyond the tolerance";
  const auto turned = [](float degrees) {
    const float a = degrees * 3.14159265f / 180.0f;
    return glm::vec3(std::sin(a), 0.0f, std::cos(a));
  };
  EXPECT_GT(scale(p, 1, n, p, 1, turned(24.0f), 4, 8), 0.0f);
  EXPECT_EQ(scale(p, 1, n, p, 1, turned(26.0f), 4, 8), 0.0f) << "normal turned by more than 25°";
  EXPECT_GT(scale(p, 1, n, p, 1, 3.0f * turned(24.0f), 4, 8), 0.0f) << "an unnormalised normal is compared by angle";
  EXPECT_EQ(scale(p, 1, n, p, 2, n, 4, 8), 0.0f) << "another object";
  EXPECT_EQ(scale(p, 0, n, p, 1, n, 4, 8), 0.0f) << "the surface appeared in the texel";
  EXPECT_EQ(scale(p, 1, n, p, 0, n, 4, 8), 0.0f) << "the surface left the texel";
}

TEST(MapHistory, ToleranceIsInUnitsOfTheShortestDiffusionLength) {
  sss::Scene scene;
  sss::SceneObject wax;
  wax.translucent = true;
  wax.material.sigma_a = {0.002f, 0.005f, 0.01f};
  wax.material.sigma_s = {1.0f, 1.2f, 1.5f};
  wax.material.g = {0.0f, 0.0f, 0.0f};
  wax.material.eta = 1.4f;
  sss::SceneObject opaque;  // ignored
  opaque.material.sigma_a = {100.0f, 100.0f, 100.0f};
  opaque.material.sigma_s = {100.0f, 100.0f, 100.0f};
  scene.objects = {wax, opaque};
  // The blue band absorbs and scatters most: its 1/σ_tr is the shortest of the wax's three; the
  // opaque object's much shorter one does not count.
  const double shortest = 1.0 / sss::samplingSigmaTr(0.01f, 1.5f, 0.0f, 1.4f);
  for (int c = 0; c < 2; ++c)
    EXPECT_GT(1.0 / sss::samplingSigmaTr(wax.material.sigma_a[c], wax.material.sigma_s[c], 0.0, 1.4), shortest);
  EXPECT_NEAR(sss::shortestDiffusionLengthMm(scene), shortest, 1e-9 * shortest);
  const sss::HistoryTolerance t = sss::historyTolerance(scene, 0.25);
  EXPECT_NEAR(t.maxMoveM, 0.25 * shortest * 1e-3, 1e-6 * shortest * 1e-3);
  EXPECT_NEAR(sss::historyTolerance(scene, 2.0).maxMoveM, 2.0 * shortest * 1e-3, 1e-6 * shortest * 1e-3);
  EXPECT_NEAR(t.minCos, std::cos(25.0 * 3.14159265358979 / 180.0), 1e-6);
}

using sss::history_glsl::sssHistoryRescale;

TEST(MapHistoryRescale, AClearChangeIsFollowedBandByBand) {
  // No noise (mean squared difference 0): the factor is each band's ratio of the coarse means.
  const glm::vec4 r = sssHistoryRescale(glm::vec3(2.0f, 1.5f, 0.6f), glm::vec3(1.0f, 1.0f, 0.5f), 0.0f, 256.0f, 4.0f);
  EXPECT_FLOAT_EQ(r.x, 2.0f);
  EXPECT_FLOAT_EQ(r.y, 1.5f);
  EXPECT_FLOAT_EQ(r.z, 1.2f);
  EXPECT_EQ(r.w, 1.0f) << "kept";
}

TEST(MapHistoryRescale, AChangeWithinTheNoiseIsShrunkTowardsOne) {
  // History means 1 in every band, this frame's 1.1: Δ = 0.1. Per texel the frames differ by a
  // mean square of 2.56 over 256 texels: σ² = 2.56 / 256 = 0.01 = Δ², so c = 1/2 and the factor is
  // 1 + 0.1 / 2.
  const glm::vec3 h(1.0f), f(1.1f);
  glm::vec4 r = sssHistoryRescale(f, h, 2.56f, 256.0f, 4.0f);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(r[c], 1.05f, 1e-5f) << c;
  // Ten times the noise: c = 0.01 / (0.01 + 0.1); a hundredth of it: nearly the whole ratio.
  r = sssHistoryRescale(f, h, 25.6f, 256.0f, 4.0f);
  EXPECT_NEAR(r.x, 1.0f + 0.1f * (0.01f / 0.11f), 1e-5f);
  r = sssHistoryRescale(f, h, 0.0256f, 256.0f, 4.0f);
  EXPECT_NEAR(r.x, 1.0f + 0.1f * (0.01f / 0.0101f), 1e-5f);
  // The same variance from a footprint of 4× the texels and 4× the mean square.
  EXPECT_NEAR(sssHistoryRescale(f, h, 10.24f, 1024.0f, 4.0f).x, 1.05f, 1e-5f);
  // No change at all: exactly 1, whatever the noise.
  r = sssHistoryRescale(h, h, 2.56f, 256.0f, 4.0f);
  for (int c = 0; c < 3; ++c) EXPECT_EQ(r[c], 1.0f) << c;
}

TEST(MapHistoryRescale, AChangeBeyondTheLimitOrLightInOneMeanOnlyResetsTheTexel) {
  const glm::vec3 h(1.0f);
  EXPECT_EQ(sssHistoryRescale(glm::vec3(4.0f), h, 0.0f, 64.0f, 4.0f).w, 1.0f) << "4: at the limit, kept";
  EXPECT_EQ(sssHistoryRescale(glm::vec3(4.1f, 1.0f, 1.0f), h, 0.0f, 64.0f, 4.0f).w, 0.0f) << "one band beyond";
  EXPECT_EQ(sssHistoryRescale(glm::vec3(1.0f, 0.24f, 1.0f), h, 0.0f, 64.0f, 4.0f).w, 0.0f) << "under 1/4";
  EXPECT_EQ(sssHistoryRescale(glm::vec3(1.0f, 1.0f, 0.0f), h, 0.0f, 64.0f, 4.0f).w, 0.0f) << "the light left a band";
  EXPECT_EQ(sssHistoryRescale(glm::vec3(1.0f), glm::vec3(1.0f, 1.0f, 0.0f), 0.0f, 64.0f, 4.0f).w, 0.0f)
      << "light came into a band";
  const glm::vec4 dark = sssHistoryRescale(glm::vec3(1.0f, 1.0f, 0.0f), glm::vec3(1.0f, 1.0f, 0.0f), 0.0f, 64.0f, 4.0f);
  EXPECT_EQ(dark.w, 1.0f) << "a band dark in both is no change";
  EXPECT_EQ(dark.z, 1.0f);
}

TEST(MapHistoryRescale, TheLevelsFootprintIsTheNearestPowerOfTwoToTheAskedLength) {
  // 512 texels over 100 mm, 5 mm diffusion length: one diffusion length is 25.6 texels, nearest
  // power of two 32 (level 5); half of it 12.8 → 16 (level 4).
  EXPECT_EQ(sss::historyRescaleLevel(512, 100.0, 5.0, 1.0), 5);
  EXPECT_EQ(sss::historyRescaleLevel(512, 100.0, 5.0, 0.5), 4);
  EXPECT_EQ(sss::historyRescaleLevel(512, 100.0, 5.0, 2.0), 6);
  EXPECT_EQ(sss::historyRescaleLevel(512, 100.0, 5.0, 0.01), sss::kHistoryRescaleMinLevel) << "under a texel";
  EXPECT_EQ(sss::historyRescaleLevel(64, 100.0, 5.0, 1.0), 3) << "3.2 texels: 8 at least";
  EXPECT_EQ(sss::historyRescaleLevel(512, 100.0, 5.0, 1000.0), 9) << "the whole map at most";
  EXPECT_EQ(sss::historyRescaleLevel(4, 100.0, 5.0, 1.0), 2) << "a 4-texel map: its top level";
}

}  // namespace
}  // namespace tallow
