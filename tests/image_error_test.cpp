// The bench's error metric (gpu/image_error.h) on image pairs whose error is known in closed form.
#include "gpu/image_error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <stdexcept>

namespace tallow {
namespace {

constexpr int kW = 7, kH = 5;

gpu::Image constant(glm::vec3 rgb, int w = kW, int h = kH) {
  gpu::Image img(w, h);
  for (auto& p : img.pixels) p = glm::vec4(rgb, 1.0f);
  return img;
}

/// Alpha 1 inside the rectangle [x0, x1) × [y0, y1), 0 elsewhere.
gpu::Image rectMask(int x0, int y0, int x1, int y1) {
  gpu::Image m(kW, kH);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) m.at(x, y).a = 1.0f;
  return m;
}

bool inside(int x, int y) { return x >= 1 && x < 5 && y >= 1 && y < 4; }

TEST(ImageError, ConstantOffsetInAllBands) {
  // Δ = δ in r, g and b: e_p = √3 δ on every pixel, so RMSE and max are both √3 δ; against a
  // constant reference c, the reference's RMS is √3 c and relative RMSE = δ / c.
  const float c = 0.25f, delta = 0.125f;  // exact in binary: no rounding in Δ
  const gpu::Image mask = rectMask(1, 1, 5, 4);
  const gpu::Image ref = constant(glm::vec3(c));
  const gpu::Image img = constant(glm::vec3(c + delta));
  const gpu::ImageError e = gpu::imageError(img, ref, mask);
  EXPECT_EQ(e.pixels, 12u);
  EXPECT_NEAR(e.rmse, std::sqrt(3.0) * delta, 1e-12);
  EXPECT_NEAR(e.maxError, std::sqrt(3.0) * delta, 1e-12);
  EXPECT_NEAR(e.relRmse, std::sqrt(3.0) * delta / (std::sqrt(3.0) * c), 1e-12);
  EXPECT_NEAR(e.meanRatio, (c + delta) / c, 1e-12);  // the bias of the mean: 1.5
}

TEST(ImageError, RelativeChangeOfTheMaskedPixels) {
  // Half the masked pixels go from 0.5 to 0.25 in every band, half from 0.25 to 0.5: the summed
  // |Δ| is 12 × 3 × 0.25 and the summed new radiance 6 × 3 × (0.25 + 0.5), so the change is 2/3.
  // Pixels outside the mask change too, and must not count.
  std::vector<std::uint8_t> mask(kW * kH, 0);
  gpu::Image before = constant(glm::vec3(9.0f)), now = constant(glm::vec3(1.0f));
  int k = 0;
  for (int y = 1; y < 4; ++y)
    for (int x = 1; x < 5; ++x, ++k) {
      mask[static_cast<std::size_t>(y * kW + x)] = 1;
      before.at(x, y) = glm::vec4(glm::vec3(k % 2 ? 0.5f : 0.25f), 1.0f);
      now.at(x, y) = glm::vec4(glm::vec3(k % 2 ? 0.25f : 0.5f), 1.0f);
    }
  EXPECT_NEAR(gpu::relativeChange(now, before, mask), (12 * 3 * 0.25) / (6 * 3 * 0.75), 1e-12);
  EXPECT_EQ(gpu::relativeChange(now, now, mask), 0.0);
  EXPECT_THROW(gpu::relativeChange(now, constant(glm::vec3(1.0f), kW + 1, kH), mask), std::invalid_argument);
  EXPECT_TRUE(std::isnan(gpu::relativeChange(constant(glm::vec3(0.0f)), constant(glm::vec3(0.0f)), mask)));
}

TEST(ImageError, MeanRatioSeesBiasThatNoiseHides) {
  // Half the pixels +δ, half −δ: the RMSE is √3 δ but the mean is unbiased (ratio 1); black on
  // black is ratio 1, light on black infinite.
  const gpu::Image mask = rectMask(0, 0, 4, 2);
  const gpu::Image ref = constant(glm::vec3(0.5f));
  gpu::Image img = ref;
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x) img.at(x, y) = glm::vec4(glm::vec3(x % 2 ? 0.625f : 0.375f), 1.0f);
  const gpu::ImageError e = gpu::imageError(img, ref, mask);
  EXPECT_NEAR(e.rmse, std::sqrt(3.0) * 0.125, 1e-12);
  EXPECT_DOUBLE_EQ(e.meanRatio, 1.0);
  const gpu::Image black = constant(glm::vec3(0.0f));
  EXPECT_DOUBLE_EQ(gpu::imageError(black, black, mask).meanRatio, 1.0);
  EXPECT_TRUE(std::isinf(gpu::imageError(ref, black, mask).meanRatio));
}

TEST(ImageError, SinglePixelDiffering) {
  // One of n object pixels off by (3, 4, 0) × s: e = 5 s there and 0 elsewhere, so RMSE = e / √n.
  const gpu::Image mask = rectMask(0, 0, kW, kH);
  const double n = kW * kH;
  const gpu::Image ref = constant(glm::vec3(0.5f));
  gpu::Image img = ref;
  const float s = 0.25f;
  img.at(3, 2) += glm::vec4(3.0f * s, -4.0f * s, 0.0f, 0.0f);
  const gpu::ImageError e = gpu::imageError(img, ref, mask);
  const double err = 5.0 * s;
  EXPECT_NEAR(e.rmse, err / std::sqrt(n), 1e-12);
  EXPECT_NEAR(e.maxError, err, 1e-12);
}

TEST(ImageError, PixelsOutsideTheMaskNeverCount) {
  const gpu::Image mask = rectMask(1, 1, 5, 4);
  const gpu::Image ref = constant(glm::vec3(0.5f, 0.25f, 1.0f));
  gpu::Image img = constant(glm::vec3(0.625f, 0.25f, 0.75f));
  const gpu::ImageError before = gpu::imageError(img, ref, mask);
  gpu::Image wildImg = img, wildRef = ref;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      if (!inside(x, y)) {
        wildImg.at(x, y) = glm::vec4(1e6f, -3e5f, 42.0f, 0.0f);
        wildRef.at(x, y) = glm::vec4(-7e4f, 9e5f, 0.0f, 1.0f);
      }
  const gpu::ImageError after = gpu::imageError(wildImg, wildRef, mask);
  EXPECT_EQ(after.pixels, before.pixels);
  EXPECT_DOUBLE_EQ(after.rmse, before.rmse);
  EXPECT_DOUBLE_EQ(after.relRmse, before.relRmse);
  EXPECT_DOUBLE_EQ(after.maxError, before.maxError);
  // Δ = (0.125, 0, −0.25) everywhere inside: e² = 0.078125; the reference's |r|² = 1.3125.
  EXPECT_NEAR(before.rmse, std::sqrt(0.078125), 1e-12);
  EXPECT_NEAR(before.relRmse, std::sqrt(0.078125 / 1.3125), 1e-12);
}

TEST(ImageError, MaskThresholdIsHalfAlpha) {
  gpu::Image mask(kW, kH);
  mask.at(0, 0).a = 0.5f;    // counts
  mask.at(1, 0).a = 0.499f;  // does not
  EXPECT_EQ(gpu::objectPixels(mask), 1u);
}

TEST(ImageError, DifferenceImageIsAbsoluteDeltaInsideTheMaskOnly) {
  const gpu::Image mask = rectMask(1, 1, 5, 4);
  const gpu::Image ref = constant(glm::vec3(0.5f));
  const gpu::Image img = constant(glm::vec3(0.25f, 0.5f, 1.25f));
  const gpu::Image d = gpu::differenceImage(img, ref, mask);
  EXPECT_FLOAT_EQ(d.at(2, 2).r, 0.25f);
  EXPECT_FLOAT_EQ(d.at(2, 2).g, 0.0f);
  EXPECT_FLOAT_EQ(d.at(2, 2).b, 0.75f);
  EXPECT_NEAR(d.at(2, 2).a, std::sqrt(0.25 * 0.25 + 0.75 * 0.75), 1e-6);
  EXPECT_EQ(d.at(0, 0), glm::vec4(0.0f));
}

TEST(ImageError, SizeMismatchAndEmptyMaskThrow) {
  const gpu::Image mask = rectMask(1, 1, 5, 4);
  const gpu::Image ref = constant(glm::vec3(0.5f));
  EXPECT_THROW(gpu::imageError(constant(glm::vec3(0.5f), kW + 1, kH), ref, mask), std::invalid_argument);
  EXPECT_THROW(gpu::imageError(ref, ref, gpu::Image(kW, kH + 1)), std::invalid_argument);
  EXPECT_THROW(gpu::imageError(ref, ref, gpu::Image(kW, kH)), std::invalid_argument);  // all alpha 0
  EXPECT_THROW(gpu::differenceImage(ref, constant(glm::vec3(0.5f), kW, kH + 2), mask), std::invalid_argument);
}

// --- Issue 17's region bias and firefly count ---------------------------------------------------

TEST(ImageErrorByHalf, SplitsTheObjectsRowsAtTheMiddle) {
  // Object rows 1..4 of 7×5 (columns 0..6): split at (1 + 4 + 1)/2 = 3, so rows 1–2 above, 3–4 below.
  gpu::Image mask(kW, kH);
  for (int y = 1; y < 5; ++y)
    for (int x = 0; x < kW; ++x) mask.at(x, y).a = 1.0f;
  const gpu::Image ref = constant({1.0f, 2.0f, 0.5f});
  gpu::Image image = ref;
  for (int y = 3; y < kH; ++y)
    for (int x = 0; x < kW; ++x) image.at(x, y) = glm::vec4(0.8f * glm::vec3(ref.at(x, y)), 1.0f);
  image.at(3, 0) = glm::vec4(100.0f);  // outside the object: never counts
  const std::optional<gpu::HalvesError> h = gpu::imageErrorByHalf(image, ref, mask);
  ASSERT_TRUE(h.has_value());
  EXPECT_EQ(h->upper.pixels, 2u * kW);
  EXPECT_EQ(h->lower.pixels, 2u * kW);
  EXPECT_DOUBLE_EQ(h->upper.meanRatio, 1.0);
  EXPECT_NEAR(h->lower.meanRatio, 0.8, 1e-7);
  // One row has no halves.
  EXPECT_FALSE(gpu::imageErrorByHalf(image, ref, rectMask(1, 2, 5, 3)).has_value());
  EXPECT_THROW(gpu::imageErrorByHalf(constant({1, 1, 1}, 3, 3), ref, mask), std::invalid_argument);
}

TEST(FireflyCount, ChannelsAboveFourTimesTheirNeighbourhoodsMedian) {
  gpu::Image image = constant({1.0f, 1.0f, 1.0f}, 20, 20);
  gpu::Image mask = constant({0, 0, 0}, 20, 20);  // alpha 1: all object
  image.at(5, 5).r = 4.01f;    // above 4×: one
  image.at(10, 10).g = 3.99f;  // below: none
  image.at(15, 15).b = 100.0f;  // one
  image.at(2, 17) = glm::vec4(5.0f, 5.0f, 5.0f, 1.0f);  // all three channels: still one pixel
  EXPECT_EQ(gpu::fireflyCount(image, mask), 3u);
  EXPECT_EQ(gpu::fireflyCount(image, mask, 3.0f), 4u);  // the factor is the threshold
}

TEST(FireflyCount, ListsEachPixelOnceWithItsFirstChannelAndRatio) {
  gpu::Image image = constant({1.0f, 2.0f, 1.0f}, 12, 10);
  gpu::Image mask = constant({0, 0, 0}, 12, 10);
  image.at(7, 2).b = 5.0f;                              // blue over its median 1: ratio 5
  image.at(3, 6) = glm::vec4(9.0f, 18.0f, 1.0f, 1.0f);  // red and green: listed once, by red (9)
  const std::vector<gpu::Firefly> found = gpu::fireflies(image, mask);
  ASSERT_EQ(found.size(), 2u);
  EXPECT_EQ(found[0].x, 7);  // row order: y = 2 first
  EXPECT_EQ(found[0].y, 2);
  EXPECT_EQ(found[0].channel, 2);
  EXPECT_FLOAT_EQ(found[0].overMedian, 5.0f);
  EXPECT_EQ(found[1].x, 3);
  EXPECT_EQ(found[1].y, 6);
  EXPECT_EQ(found[1].channel, 0);
  EXPECT_FLOAT_EQ(found[1].overMedian, 9.0f);
  EXPECT_EQ(gpu::fireflyCount(image, mask), found.size());
  // The ratio of a pixel that is no firefly: green 3.5 over the median 2 of its window.
  image.at(9, 8).g = 3.5f;
  EXPECT_FLOAT_EQ(gpu::fireflyRatio(image, mask, 9, 8, 1), 1.75f);
  // A median of 0: infinite over a lit pixel, NaN over a black one.
  gpu::Image black = constant({0, 0, 0}, 3, 3);
  const gpu::Image blackMask = constant({0, 0, 0}, 3, 3);
  EXPECT_TRUE(std::isnan(gpu::fireflyRatio(black, blackMask, 1, 1, 0)));
  black.at(1, 1).r = 1.0f;
  EXPECT_TRUE(std::isinf(gpu::fireflyRatio(black, blackMask, 1, 1, 0)));
  EXPECT_THROW(gpu::fireflyRatio(image, mask, 12, 0, 0), std::invalid_argument);
  EXPECT_THROW(gpu::fireflyRatio(image, mask, 0, 0, 3), std::invalid_argument);
}

TEST(FireflyCount, EdgesAndTheObjectsBorderAreNoFireflies) {
  // A step from 1 to 10 at x = 10: a pixel on either side has a majority of its side in its 5×5
  // window, so its median is its own level.
  gpu::Image step = constant({1.0f, 1.0f, 1.0f}, 20, 20);
  for (int y = 0; y < 20; ++y)
    for (int x = 10; x < 20; ++x) step.at(x, y) = glm::vec4(10.0f, 10.0f, 10.0f, 1.0f);
  EXPECT_EQ(gpu::fireflyCount(step, constant({0, 0, 0}, 20, 20)), 0u);
  // A one-pixel-wide object on black: the median is over object pixels only (with the background
  // it would be 0 and every object pixel would count).
  gpu::Image column = constant({0.0f, 0.0f, 0.0f}, 9, 9);
  gpu::Image mask(9, 9);
  for (int y = 0; y < 9; ++y) column.at(4, y) = glm::vec4(1.0f), mask.at(4, y).a = 1.0f;
  EXPECT_EQ(gpu::fireflyCount(column, mask), 0u);
  EXPECT_THROW(gpu::fireflyCount(column, step), std::invalid_argument);
}

// Issue 37, point 3: a NaN in either image used to leave every metric at 0 (std::max and "> 0"
// skip NaN), so a broken reference scored a perfect match.
TEST(ImageError, ANonFinitePixelMakesTheErrorUndefinedNotZero) {
  const gpu::Image mask = rectMask(1, 1, 5, 4);
  const gpu::Image ref = constant(glm::vec3(0.5f));
  gpu::Image nanRef = ref, infImage = ref;
  nanRef.at(2, 2) = glm::vec4(std::nanf(""), 0.5f, 0.5f, 1.0f);
  infImage.at(3, 1).g = INFINITY;
  const gpu::ImageError a = gpu::imageError(ref, nanRef, mask);
  EXPECT_TRUE(std::isnan(a.rmse));
  EXPECT_TRUE(std::isnan(a.relRmse));
  EXPECT_TRUE(std::isnan(a.maxError));
  EXPECT_TRUE(std::isnan(a.meanRatio));
  EXPECT_EQ(a.nonFiniteReference, 1u);
  EXPECT_EQ(a.nonFiniteImage, 0u);
  EXPECT_FALSE(a.finite());
  const gpu::ImageError b = gpu::imageError(infImage, ref, mask);
  EXPECT_TRUE(std::isnan(b.relRmse));
  EXPECT_EQ(b.nonFiniteImage, 1u);
  // Outside the mask a NaN is not compared, so not counted.
  gpu::Image outside = ref;
  outside.at(0, 0).r = std::nanf("");
  EXPECT_TRUE(gpu::imageError(outside, ref, mask).finite());
  EXPECT_EQ(gpu::nonFinitePixels(outside, &mask), 0u);
  EXPECT_EQ(gpu::nonFinitePixels(outside), 1u);
}

TEST(ImageError, NonFinitePixelsLeftOutWhenAskedAreCounted) {
  // Image 0.625 against 0.5 everywhere but one NaN pixel of the reference: left out, the other 11
  // pixels give Δ = 0.125 in every band, relative RMSE 0.125 / 0.5 = 0.25.
  const gpu::Image mask = rectMask(1, 1, 5, 4);
  gpu::Image ref = constant(glm::vec3(0.5f));
  ref.at(2, 2).b = std::nanf("");
  const gpu::Image img = constant(glm::vec3(0.625f));
  gpu::ImageErrorOptions options;
  options.skipNonFinite = true;
  const gpu::ImageError e = gpu::imageError(img, ref, mask, options);
  EXPECT_EQ(e.pixels, 11u);
  EXPECT_EQ(e.skippedNonFinite, 1u);
  EXPECT_EQ(e.nonFiniteReference, 1u);
  EXPECT_NEAR(e.relRmse, 0.25, 1e-12);
  EXPECT_NEAR(e.meanRatio, 1.25, 1e-12);
  // Every compared pixel left out: nothing to measure, undefined again.
  gpu::Image allNan = constant(glm::vec3(std::nanf("")));
  EXPECT_TRUE(std::isnan(gpu::imageError(img, allNan, mask, options).relRmse));
}

}  // namespace
}  // namespace tallow
