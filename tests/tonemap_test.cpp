// The hue-preserving tone map (render.tonemap=hue-preserving, shaders/common/tonemap.glsl) through
// its C++ face: hue kept as saturated HDR colours brighten, monotonic, black to 0, very bright to
// white, never a clipped channel. The hue is measured by an independent formula (HSV's hue angle,
// which scaling RGB by a positive factor and adding grey leave unchanged), and the per-channel
// ACES curve is run through the same checks to show that they tell the two kinds of operator apart.
#include "gpu/tonemap.h"

#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace tallow::gpu {
namespace {

constexpr ToneMapSettings kHue{ToneMap::HuePreserving, 0.0f};
constexpr ToneMapSettings kAces{ToneMap::Aces, 0.0f};

/// HSV hue angle in degrees [0, 360) of an RGB triple (Smith 1978), from max, min and the order of
/// the channels; undefined (returned as 0) for grey.
double hueDegrees(glm::dvec3 c) {
  const double hi = std::max({c.r, c.g, c.b}), lo = std::min({c.r, c.g, c.b}), d = hi - lo;
  if (!(d > 0.0)) return 0.0;
  double h = 0.0;
  if (hi == c.r) h = std::fmod((c.g - c.b) / d + 6.0, 6.0);
  else if (hi == c.g) h = (c.b - c.r) / d + 2.0;
  else h = (c.r - c.g) / d + 4.0;
  return 60.0 * h;
}

double saturation(glm::dvec3 c) {
  const double hi = std::max({c.r, c.g, c.b});
  return hi > 0.0 ? (hi - std::min({c.r, c.g, c.b})) / hi : 0.0;
}

double hueDifference(double a, double b) {
  const double d = std::fmod(std::abs(a - b), 360.0);
  return std::min(d, 360.0 - d);
}

double luminance(glm::vec3 c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

/// Saturated colours: the primaries, a candle-flame orange, a deep sky blue, a skin-like red.
const std::vector<glm::vec3>& saturatedColours() {
  static const std::vector<glm::vec3> colours{{1.0f, 0.0f, 0.0f},  {0.0f, 1.0f, 0.0f},   {0.0f, 0.0f, 1.0f},
                                              {1.0f, 0.45f, 0.08f}, {0.05f, 0.25f, 1.0f}, {0.9f, 0.35f, 0.3f}};
  return colours;
}

/// Largest hue change (degrees) of `settings` over exposures 2^-8 … 2^12 of each colour, among the
/// outputs still saturated enough (≥ 5%) for the hue to be well defined.
double worstHueDrift(const ToneMapSettings& settings) {
  double worst = 0.0;
  for (const glm::vec3& colour : saturatedColours()) {
    const double hue = hueDegrees(glm::dvec3(colour));
    for (int ev = -8; ev <= 12; ++ev) {
      const glm::dvec3 out(toneMapLinear(colour * std::exp2(static_cast<float>(ev)), settings));
      if (saturation(out) < 0.05) continue;
      worst = std::max(worst, hueDifference(hueDegrees(out), hue));
    }
  }
  return worst;
}

TEST(HuePreservingToneMap, KeepsTheHueOfSaturatedColoursAsTheyBrighten) {
  // By construction (grey added, positive scale) the hue is exact up to float rounding; 0.05°
  // leaves room for that and nothing else.
  EXPECT_LT(worstHueDrift(kHue), 0.05);
  // The per-channel ACES curve shifts the orange toward yellow as it brightens: the check sees it.
  EXPECT_GT(worstHueDrift(kAces), 5.0);
}

TEST(HuePreservingToneMap, KeepsChannelRatiosWhileTheColourFitsWellUnderWhite) {
  // Dim colours: Y_d small, the brightest channel far below 1, so s = (1 + s_max^-4)^-1/4 > 0.999
  // and the output is the input scaled (ratios within 0.2%).
  for (const glm::vec3& colour : saturatedColours()) {
    const glm::vec3 in = colour * 0.02f;
    const glm::vec3 out = toneMapLinear(in, kHue);
    const int k = in.r >= in.g && in.r >= in.b ? 0 : (in.g >= in.b ? 1 : 2);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(out[c] / out[k], in[c] / in[k], 2e-3) << c;
  }
}

TEST(HuePreservingToneMap, MonotonicInLuminanceAndInEveryChannel) {
  for (const glm::vec3& colour : saturatedColours()) {
    glm::vec3 previous(0.0f);
    double previousY = 0.0;
    // 2^-12 … 2^12 in eighths of a stop (beyond, Y_d is within a float's step of 1 between steps).
    for (int step = -12 * 8; step <= 12 * 8; ++step) {
      const glm::vec3 out = toneMapLinear(colour * std::exp2(static_cast<float>(step) / 8.0f), kHue);
      const double y = luminance(out);
      EXPECT_GT(y, previousY) << "step " << step;
      // Each channel is non-decreasing in exact arithmetic (Y_d rises, the saturation kept falls and
      // the brightest channel tends to 1 from below); near 1 the float result may step back by a
      // rounding unit or two (6e-8 each), never more.
      for (int c = 0; c < 3; ++c)
        EXPECT_GE(out[c], previous[c] - 2.5e-7f) << "step " << step << " channel " << c;
      previous = out;
      previousY = y;
    }
  }
}

TEST(HuePreservingToneMap, BlackIsZeroAndMidGreyStaysMidGrey) {
  EXPECT_EQ(toneMapLinear(glm::vec3(0.0f), kHue), glm::vec3(0.0f));
  EXPECT_EQ(toneMapLinear(glm::vec3(-1.0f, 0.0f, -3.0f), kHue), glm::vec3(0.0f));  // negative radiance is black
  // Continuous at black: Y_d ≈ (Y/k)^1.5 → 0.
  EXPECT_LT(toneMapLinear(glm::vec3(1e-6f, 2e-6f, 1e-6f), kHue).g, 1e-6f);
  // kⁿ = gⁿ (1/g − 1) makes Y_d(g) = gⁿ / (gⁿ + gⁿ (1/g − 1)) = g: 0.18 in, 0.18 out, and grey stays grey.
  const glm::vec3 grey = toneMapLinear(glm::vec3(0.18f), kHue);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(grey[c], 0.18f, 1e-6f);
}

TEST(HuePreservingToneMap, VeryBrightGoesToWhiteWithoutClippingAChannel) {
  for (const glm::vec3& colour : saturatedColours()) {
    // Never a channel at 1 before the final clamp: the brightest one stays below it, however bright.
    for (int ev = 0; ev <= 40; ev += 4) {
      const glm::vec3 out = toneMapLinear(colour * std::exp2(static_cast<float>(ev)), kHue);
      EXPECT_LE(std::max({out.r, out.g, out.b}), 1.0f);
    }
    // 2^20 times brighter: white, every channel within 0.1% of 1 — a primary does not stay a primary.
    const glm::vec3 white = toneMapLinear(colour * std::exp2(20.0f), kHue);
    for (int c = 0; c < 3; ++c) EXPECT_GT(white[c], 0.999f) << c;
  }
  // ACES clips per channel: pure red stays (1, 0, 0) however bright.
  const glm::vec3 acesRed = toneMapLinear(glm::vec3(1.0f, 0.0f, 0.0f) * std::exp2(20.0f), kAces);
  EXPECT_EQ(acesRed.g, 0.0f);
  // Huge and denormal inputs give finite outputs.
  for (float v : {3e38f, 1e-40f}) {
    const glm::vec3 out = toneMapToSrgb(glm::vec3(v, 0.5f * v, 0.0f), kHue);
    for (int c = 0; c < 3; ++c) EXPECT_TRUE(std::isfinite(out[c])) << v;
  }
}

TEST(HuePreservingToneMap, ParsesAndNamesLikeTheOtherOperators) {
  EXPECT_EQ(parseToneMap("hue-preserving"), ToneMap::HuePreserving);
  EXPECT_EQ(toneMapName(ToneMap::HuePreserving), "hue-preserving");
  EXPECT_THROW(parseToneMap("agx"), std::invalid_argument);
}

}  // namespace
}  // namespace tallow::gpu
