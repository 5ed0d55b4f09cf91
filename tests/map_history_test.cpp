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

}  // namespace
}  // namespace tallow
