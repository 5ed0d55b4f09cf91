// The bench's speed-against-error plot (app/commands/bench_plot.h) places its labels without
// overlaps, and the comparison pictures' difference (app/commands/comparison_figure.h) is the
// bench's metric per pixel.
#include "app/commands/bench_plot.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "app/commands/comparison_figure.h"
#include "gpu/image.h"

namespace tallow::app {
namespace {

TEST(BenchPlot, LabelsOverlapNeitherEachOtherNorTheMarkers) {
  const PixelRect area{90, 70, 740, 550};
  constexpr double kMarker = 6.0;
  std::mt19937 random(7);
  // Clusters like a sweep's: points a few pixels apart, plus a spread-out rest.
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<glm::dvec2> anchors, sizes;
    std::normal_distribution<double> near(0.0, 6.0);
    std::uniform_real_distribution<double> x(area.x0 + 20, area.x1 - 20), y(area.y0 + 20, area.y1 - 20);
    const glm::dvec2 centre{x(random), y(random)};
    for (int i = 0; i < 12; ++i) {
      anchors.push_back(i < 8 ? centre + glm::dvec2(near(random), near(random)) : glm::dvec2(x(random), y(random)));
      sizes.emplace_back(6.2 * (4 + i % 9), 13.0);
    }
    const std::vector<PixelRect> reserved = {{area.x1 - 120, 300, area.x1 - 4, 313}};
    const std::vector<LabelPlacement> placed = placeLabels(anchors, sizes, area, kMarker, reserved);
    ASSERT_EQ(placed.size(), anchors.size());
    int count = 0;
    for (std::size_t i = 0; i < placed.size(); ++i) {
      if (!placed[i].placed) continue;
      ++count;
      const PixelRect& b = placed[i].box;
      EXPECT_TRUE(b.inside(area));
      EXPECT_NEAR(b.x1 - b.x0, sizes[i].x, 1e-9);
      EXPECT_FALSE(b.overlaps(reserved[0])) << "label " << i << " over the reference line's label";
      for (const glm::dvec2& a : anchors)
        EXPECT_FALSE(b.overlaps({a.x - kMarker, a.y - kMarker, a.x + kMarker, a.y + kMarker})) << "label " << i;
      for (std::size_t j = 0; j < i; ++j) {
        if (placed[j].placed) {
          EXPECT_FALSE(b.overlaps(placed[j].box)) << "labels " << i << " and " << j;
        }
      }
    }
    // Eight labels within a few pixels of each other still all find room, on farther rings.
    EXPECT_EQ(count, 12) << "trial " << trial;
  }
}

TEST(BenchPlot, ALabelGoesRightOfALonePoint) {
  const std::vector<LabelPlacement> placed =
      placeLabels({{200, 200}}, {{40, 13}}, PixelRect{0, 0, 800, 600}, 6.0);
  ASSERT_TRUE(placed[0].placed);
  EXPECT_FALSE(placed[0].leader);
  EXPECT_GT(placed[0].box.x0, 206.0);
  EXPECT_NEAR((placed[0].box.y0 + placed[0].box.y1) / 2.0, 200.0, 1e-9);
}

TEST(ComparisonFigure, TheDifferenceIsTheBenchsMetricPerPixel) {
  gpu::Image reference(2, 2), image(2, 2), mask(2, 2);
  reference.pixels = {glm::vec4(1, 0, 0, 1), glm::vec4(0, 1, 0, 1), glm::vec4(0, 0, 1, 1), glm::vec4(5, 5, 5, 1)};
  image.pixels = {glm::vec4(1, 0, 0, 1), glm::vec4(0, 2, 0, 1), glm::vec4(0, 0, 1.5, 1), glm::vec4(0, 0, 0, 1)};
  mask.pixels = {glm::vec4(0, 0, 0, 1), glm::vec4(0, 0, 0, 1), glm::vec4(0, 0, 0, 1), glm::vec4(0, 0, 0, 0)};
  // RMS of the reference over the three masked pixels: 1; |Δ| 0, 1, 0.5; the last pixel is outside.
  const std::vector<float> d = relativeDifference(image, reference, &mask);
  EXPECT_FLOAT_EQ(d[0], 0.0f);
  EXPECT_FLOAT_EQ(d[1], 1.0f);
  EXPECT_FLOAT_EQ(d[2], 0.5f);
  EXPECT_TRUE(std::isnan(d[3]));
  // Their RMS is the bench's relative RMSE: √((0 + 1 + 0.25) / 3).
  EXPECT_NEAR(std::sqrt((d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) / 3.0), std::sqrt(1.25 / 3.0), 1e-7);
  EXPECT_THROW(relativeDifference(gpu::Image(3, 2), reference, nullptr), std::invalid_argument);

  EXPECT_DOUBLE_EQ(niceScale({0.01f, 0.03f, 0.04f}, 1.0), 0.05);
  EXPECT_DOUBLE_EQ(niceScale({0.2f}, 1.0), 0.2);
  EXPECT_DOUBLE_EQ(niceScale({0.21f}, 1.0), 0.5);
  EXPECT_DOUBLE_EQ(niceScale({12.0f, std::nanf("")}, 1.0), 20.0);
  EXPECT_DOUBLE_EQ(niceScale({0.0f}, 1.0), 1.0) << "nothing to scale";
  // The 99th percentile leaves a lone outlier out.
  std::vector<float> many(1000, 0.03f);
  many.back() = 50.0f;
  EXPECT_DOUBLE_EQ(niceScale(many, 0.99), 0.05);
}

}  // namespace
}  // namespace tallow::app
