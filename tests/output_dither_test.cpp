// The 8-bit outputs' dither (shaders/common/tonemap.glsl through gpu::toneMappedRgb8): a dark
// gradient written to PNG keeps its mean level everywhere (no bands: the mean of a block equals the
// signal to a small fraction of a level, where rounding is off by up to half a level and constant
// over whole rings), the noise is triangular on (−1, 1) levels (mean 0, variance 1/6, per Lipshitz et
// al. 1992), and black and white stay exact.
#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

#include "gpu/image.h"
#include "gpu/image_io.h"
#include "gpu/tonemap.h"

namespace tallow::gpu {
namespace {

constexpr ToneMapSettings kClamp{ToneMap::Clamp, 0.0f};

/// A uniform image whose sRGB encoding is `level` / 255 (level need not be whole).
Image uniformAtLevel(int size, double level) {
  Image image(size, size);
  // Inverse of the sRGB transfer function (IEC 61966-2-1), to land on the level exactly.
  const double e = level / 255.0;
  const double linear = e <= 0.04045 ? e / 12.92 : std::pow((e + 0.055) / 1.055, 2.4);
  for (glm::vec4& p : image.pixels) p = glm::vec4(glm::vec3(static_cast<float>(linear)), 1.0f);
  return image;
}

double meanByte(const std::vector<std::uint8_t>& bytes) {
  double sum = 0.0;
  for (std::uint8_t b : bytes) sum += b;
  return sum / static_cast<double>(bytes.size());
}

TEST(OutputDither, KeepsTheMeanLevelBetweenTwoLevels) {
  // Between levels 10 and 11, where a dark table's glow fades: rounding gives 10 everywhere for
  // 10.3 (an error of 0.3 levels over the whole ring), the dithered mean is 10.3.
  for (double level : {10.3, 10.5, 10.75, 3.1, 200.6}) {
    const std::vector<std::uint8_t> bytes = toneMappedRgb8(uniformAtLevel(128, level), kClamp);
    const double mean = meanByte(bytes);
    std::printf("[ dither  ] level %.2f: mean byte %.4f\n", level, mean);
    EXPECT_NEAR(mean, level, 0.03) << "the dithered mean is the signal";
  }
}

TEST(OutputDither, NoiseIsTriangularOnPlusMinusOneLevel) {
  double sum = 0.0, sum2 = 0.0;
  int below = 0;
  constexpr int kN = 256;
  for (int y = 0; y < kN; ++y)
    for (int x = 0; x < kN; ++x) {
      const double d = ditherLevels(x, y);
      ASSERT_GT(d, -1.0);
      ASSERT_LT(d, 1.0);
      sum += d;
      sum2 += d * d;
      below += std::abs(d) < 0.5 ? 1 : 0;
    }
  const double n = kN * kN, mean = sum / n, variance = sum2 / n - mean * mean;
  EXPECT_NEAR(mean, 0.0, 0.01);
  EXPECT_NEAR(variance, 1.0 / 6.0, 0.005) << "two uniforms on [0, 1): variance 2/12";
  EXPECT_NEAR(below / n, 0.75, 0.01) << "P(|d| < 1/2) = 3/4 for the triangular density";
}

TEST(OutputDither, BlackAndWhiteStayExact) {
  for (const std::uint8_t b : toneMappedRgb8(uniformAtLevel(32, 0.0), kClamp)) ASSERT_EQ(b, 0);
  for (const std::uint8_t b : toneMappedRgb8(uniformAtLevel(32, 255.0), kClamp)) ASSERT_EQ(b, 255);
  Image nan(4, 4);
  for (glm::vec4& p : nan.pixels) p = glm::vec4(std::nanf(""));
  for (const std::uint8_t b : toneMappedRgb8(nan, kClamp)) ASSERT_EQ(b, 0);
}

TEST(OutputDither, WholeLevelsMoveByAtMostOne) {
  const std::vector<std::uint8_t> bytes = toneMappedRgb8(uniformAtLevel(64, 40.0), kClamp);
  for (const std::uint8_t b : bytes) {
    ASSERT_GE(b, 39);
    ASSERT_LE(b, 41);
  }
}

}  // namespace
}  // namespace tallow::gpu
