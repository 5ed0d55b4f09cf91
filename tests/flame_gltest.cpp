// The candle's visible flame (issue 16, point 5): drawn after the surface, brighter than any wax,
// kept out of everything the light transport reads, and as bright in total as its point light.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "sss/flame_pass.h"
#include "support/render_support.h"

namespace tallow {
namespace {

double luminance(const glm::vec4& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

TEST(Flame, EffectiveAreaIsTheProfileIntegratedNumerically) {
  // flame.frag's radiance profile, integrated by the midpoint rule: 3/2 (1 − x²) across the row of
  // half-width w(v) = √v (1 − v) / f(1/3), times 1.3 − 0.6 v, over v ∈ [0, 1].
  const sss::FlameShape shape;
  const int n = 2000;
  const double widest = std::sqrt(1.0 / 3.0) * 2.0 / 3.0;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double v = (i + 0.5) / n;
    const double w = std::sqrt(v) * (1.0 - v) / widest;
    for (int j = 0; j < n; ++j) {
      const double x = -1.0 + 2.0 * (j + 0.5) / n;  // u / w
      sum += 1.5 * (1.0 - x * x) * (1.3 - 0.6 * v) * (2.0 * w / n) * (1.0 / n);
    }
  }
  EXPECT_NEAR(shape.effectiveArea() / (sum * shape.halfWidth * shape.height), 1.0, 1e-4);
}

TEST(Flame, IsDrawnOverThePictureAndOutshinesTheWax) {
  test::PresetSession session("candle", {"render.width=96", "render.height=54", "field.res=48", "sss.maps=4",
                                         "sss.samples=2", "sss.frames=1", "sss.map_size=64", "sss.light_map_size=64",
                                         "vpl.count=0"});
  const double t = 12.0;
  session.render(t);
  const gpu::Image with = session.render(t);  // converged maps
  const std::vector<std::uint8_t> wax = session.renderer().translucentMask();
  session.settings().flame = false;
  sss::FrameTimings timings;
  const gpu::Image without = session.render(t, &timings);
  // Turning the flame off reruns nothing but the camera pass: the flame is in no map or G-buffer.
  ASSERT_EQ(timings.passes.size(), 1u);
  EXPECT_EQ(timings.passes[0].name, "surface");
  double flameMax = 0.0, waxMax = 0.0;
  int flamePixels = 0;
  for (std::size_t i = 0; i < with.pixels.size(); ++i) {
    const double added = luminance(with.pixels[i]) - luminance(without.pixels[i]);
    EXPECT_GE(added, -1e-6) << "pixel " << i << ": the flame only adds light";
    if (added > 0.0) {
      ++flamePixels;
      flameMax = std::max(flameMax, luminance(with.pixels[i]));
    }
    if (wax[i]) waxMax = std::max(waxMax, luminance(without.pixels[i]));
  }
  EXPECT_GT(flamePixels, 3) << "the flame stands above the rim, in view";
  EXPECT_LT(flamePixels, static_cast<int>(with.pixels.size()) / 50) << "a flame, not a glow over the picture";
  ASSERT_GT(waxMax, 0.0);
  // HDR well above the wax: radiance = intensity / area (0.02 W/sr over ~80 mm²) against wax lit
  // from 5 mm away.
  EXPECT_GT(flameMax, 3.0 * waxMax) << "flame " << flameMax << ", brightest wax " << waxMax;
}

}  // namespace
}  // namespace tallow
