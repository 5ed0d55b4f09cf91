// The sub-pixel positions of render.aa and of the reference's box filter (sss/pixel_jitter.h):
// position 0 is the pixel centre; every first 2^k positions put one x in each of 2^k equal strips
// of the pixel and every first 3^k one y in each of 3^k strips (the van der Corput property of the
// Halton sequence, which the rotation by ½ keeps), so their mean tends to the box filter.
#include "sss/pixel_jitter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

namespace tallow::sss {
namespace {

TEST(PixelJitter, StartsAtTheCentre) {
  EXPECT_EQ(pixelJitter(0), glm::dvec2(0.0));
  EXPECT_DOUBLE_EQ(radicalInverse(1, 2), 0.5);
  EXPECT_DOUBLE_EQ(radicalInverse(6, 2), 0.375);  // 110₂ → 0.011₂
  EXPECT_DOUBLE_EQ(radicalInverse(5, 3), 7.0 / 9.0);  // 12₃ → 0.21₃
}

TEST(PixelJitter, StratifiesThePixel) {
  for (unsigned n : {2u, 4u, 8u, 16u, 64u}) {
    std::set<int> strips;
    for (unsigned k = 0; k < n; ++k) {
      const glm::dvec2 j = pixelJitter(k);
      ASSERT_GE(j.x, -0.5);
      ASSERT_LT(j.x, 0.5);
      strips.insert(static_cast<int>(std::floor((j.x + 0.5) * n)));
    }
    EXPECT_EQ(strips.size(), n) << "x of the first " << n << " positions";
  }
  for (unsigned n : {3u, 9u, 27u}) {
    std::set<int> strips;
    for (unsigned k = 0; k < n; ++k) {
      const glm::dvec2 j = pixelJitter(k);
      ASSERT_GE(j.y, -0.5);
      ASSERT_LT(j.y, 0.5);
      strips.insert(static_cast<int>(std::floor((j.y + 0.5) * n + 1e-9)));
    }
    EXPECT_EQ(strips.size(), n) << "y of the first " << n << " positions";
  }
}

}  // namespace
}  // namespace tallow::sss
