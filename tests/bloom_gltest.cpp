// render.bloom (sss/bloom.h): the glare keeps the picture's flux (an energy-conserving PSF), shows
// a glow around the candle's flame in the picture shown — the pixels 2 to 8 px outside the flame at
// 640×360 brighten by at least 0.02 in sRGB (issue 36) — and leaves the radiance (the EXR) alone.
#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "gpu/tonemap.h"
#include "support/render_support.h"

namespace tallow {
namespace {

constexpr int kW = 640, kH = 360;

double luma(const glm::vec3& srgb) { return 0.2126 * srgb.r + 0.7152 * srgb.g + 0.0722 * srgb.b; }

glm::dvec3 flux(const gpu::Image& image) {
  glm::dvec3 sum(0.0);
  for (const glm::vec4& p : image.pixels) sum += glm::dvec3(glm::vec3(p));
  return sum;
}

struct Pictures {
  gpu::Image radiance, shown;
};

/// The default candle at 640×360 (render.bloom as the preset sets it unless `bloom` is given), without
/// render.local_exposure's adaptation, which changes the picture shown after the glare.
Pictures candle(bool flame, std::optional<float> bloom = std::nullopt) {
  std::vector<std::string> sets = {"render.width=640", "render.height=360", "render.aa=1", "sss.frames=1",
                                   "render.flame=" + std::string(flame ? "true" : "false"), "flame.flicker=0",
                                   "render.local_exposure=0"};
  if (bloom) sets.push_back("render.bloom=" + std::to_string(*bloom));
  test::PresetSession s("candle", sets);
  if (!bloom) {
    EXPECT_GT(s.settings().bloom, 0.0f) << "the candle preset turns the glare on";
  }
  s.render(s.scene().startS);
  return {s.renderer().readRadiance(), s.renderer().readShown()};
}

TEST(Bloom, KeepsTheFluxAndGlowsAroundTheFlame) {
  const Pictures lit = candle(true), dark = candle(false);
  const gpu::ToneMapSettings toneMap{gpu::ToneMap::HuePreserving, -1.0f};  // the candle preset's
  // The radiance is the scene's: the glare is only in the picture shown.
  const glm::dvec3 before = flux(lit.radiance), after = flux(lit.shown);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(after[c] / before[c], 1.0, 0.01) << "band " << c << ": the flux is kept";
  EXPECT_NE(lit.radiance.pixels, lit.shown.pixels);
  // The flame's own pixels: those it brightens by more than 0.25 (issue 35's definition).
  std::vector<char> flame(static_cast<std::size_t>(kW) * kH, 0);
  int flamePixels = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const double d = luma(gpu::toneMapToSrgb(glm::vec3(lit.radiance.at(x, y)), toneMap)) -
                       luma(gpu::toneMapToSrgb(glm::vec3(dark.radiance.at(x, y)), toneMap));
      if (d > 0.25) flame[static_cast<std::size_t>(y) * kW + x] = 1, ++flamePixels;
    }
  ASSERT_GT(flamePixels, 50);
  // The ring: pixels whose nearest flame pixel is 2 to 8 px away (Chebyshev distance).
  double withGlare = 0.0, withoutGlare = 0.0;
  int ring = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      int nearest = 99;
      for (int dy = -8; dy <= 8; ++dy)
        for (int dx = -8; dx <= 8; ++dx) {
          const int u = x + dx, v = y + dy;
          if (u < 0 || v < 0 || u >= kW || v >= kH || !flame[static_cast<std::size_t>(v) * kW + u]) continue;
          nearest = std::min(nearest, std::max(std::abs(dx), std::abs(dy)));
        }
      if (nearest < 2 || nearest > 8) continue;
      const auto shownBy = [&](const gpu::Image& a, const gpu::Image& b) {
        return luma(gpu::toneMapToSrgb(glm::vec3(a.at(x, y)), toneMap)) - luma(gpu::toneMapToSrgb(glm::vec3(b.at(x, y)), toneMap));
      };
      withGlare += shownBy(lit.shown, dark.shown);
      withoutGlare += shownBy(lit.radiance, dark.radiance);
      ++ring;
    }
  ASSERT_GT(ring, 100);
  withGlare /= ring;
  withoutGlare /= ring;
  std::printf("[ bloom   ] %d flame pixels; the %d pixels 2-8 px outside brighten by %.4f with the preset's render.bloom, "
              "%.4f without (sRGB)\n",
              flamePixels, ring, withGlare, withoutGlare);
  EXPECT_GE(withGlare, 0.02) << "issue 36: a glow around the flame";
  EXPECT_LT(withoutGlare, 0.02) << "without the glare the ring barely changes: the test tells them apart";
}

TEST(Bloom, OffShowsTheRadiance) {
  test::PresetSession s("candle", {"render.width=64", "render.height=36", "render.bloom=0", "render.local_exposure=0",
                                         "sss.frames=1"});
  EXPECT_EQ(s.settings().bloom, 0.0f);
  s.render(s.scene().startS);
  const Pictures p{s.renderer().readRadiance(), s.renderer().readShown()};
  EXPECT_EQ(p.radiance.pixels, p.shown.pixels);
}

}  // namespace
}  // namespace tallow
