// render.local_exposure (sss/local_exposure.h, shaders/camera/local_exposure.comp) on pictures whose
// answer is known: a uniform region's base layer is its own log luminance, so a region d stops
// below mid grey (at the exposure scale) is lifted by exactly s·d stops; a region above mid grey is
// unchanged, bit for bit; next to a 10-stop edge the dark side is lifted as its interior (the
// bilateral grid keeps the bright side out of the dark side's base: no halo), where a base without
// the range axis would lift it less; within a region, local contrast is kept far better than a global
// curve of the same strength would keep it; a pixel blended from both sides of an edge shows the blend
// of what the sides show.
#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "gpu/gl_context.h"
#include "gpu/gl_objects.h"
#include "gpu/readback.h"
#include "gpu/shader_library.h"
#include "sss/local_exposure.h"

namespace tallow {
namespace {

constexpr int kW = 256, kH = 128;
constexpr double kGreyStops = -2.4739311883324122;  // log2 0.18

double luminance(const glm::vec4& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

/// The picture `pixels` (kW × kH, linear) through LocalExposure at strength s and exposure scale e.
gpu::Image adapted(const std::vector<glm::vec4>& pixels, float s, float e) {
  const gpu::ShaderLibrary shaders;
  sss::LocalExposure local(shaders);
  gpu::Texture picture = gpu::Texture::create2D(GL_RGBA32F, kW, kH);
  picture.setFilter(GL_NEAREST, GL_NEAREST);
  glTextureSubImage2D(picture.id(), 0, 0, 0, kW, kH, GL_RGBA, GL_FLOAT, pixels.data());
  local.apply(picture, s, e);
  return gpu::readTexture(local.output());
}

/// Stops by which the pixel (x, y) was lifted.
double liftAt(const gpu::Image& after, const std::vector<glm::vec4>& before, int x, int y) {
  return std::log2(luminance(after.at(x, y)) / luminance(before[static_cast<std::size_t>(y) * kW + x]));
}

class LocalExposureGL : public ::testing::Test {
 protected:
  std::unique_ptr<gpu::GlContext> context_ = gpu::GlContext::create(gpu::ContextOptions{});
};

TEST_F(LocalExposureGL, LiftsAUniformRegionBySTimesItsStopsBelowMidGreyAndLeavesBrightRegions) {
  // Left: an orange above mid grey at e = 0.5; right: the same orange 10 stops darker.
  const glm::vec4 bright(1.2f, 0.6f, 0.2f, 1.0f), dark = bright * std::exp2(-10.0f);
  std::vector<glm::vec4> pixels(static_cast<std::size_t>(kW) * kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) pixels[static_cast<std::size_t>(y) * kW + x] = x < kW / 2 ? bright : glm::vec4(glm::vec3(dark), 1.0f);
  const float s = 0.6f, e = 0.5f;
  const gpu::Image after = adapted(pixels, s, e);
  const double darkStops = std::log2(e * luminance(dark));
  const double expected = s * (kGreyStops - darkStops);  // ≈ 4.4 stops
  double interior = 0.0, nearEdge = 99.0, brightChange = 0.0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      if (x < kW / 2) {
        for (int c = 0; c < 4; ++c) brightChange = std::max(brightChange, double(std::abs(after.at(x, y)[c] - pixels[static_cast<std::size_t>(y) * kW + x][c])));
        continue;
      }
      const double lift = liftAt(after, pixels, x, y);
      if (x >= kW / 2 + 40) interior = std::max(interior, std::abs(lift - expected));
      if (x < kW / 2 + 3) nearEdge = std::min(nearEdge, lift);
      // The colour is scaled, not changed: hue and saturation kept.
      const glm::vec4 p = after.at(x, y);
      EXPECT_NEAR(p.g / p.r, 0.5, 1e-5);
    }
  std::printf("[ local   ] s %.1f: the dark side %.2f stops under mid grey lifted %.4f stops (worst interior error "
              "%.1e), within 3 px of the edge at least %.4f; the bright side changed by at most %.1e\n",
              s, kGreyStops - darkStops, expected, interior, nearEdge, brightChange);
  EXPECT_LT(interior, 1e-3) << "a uniform region: its base is its own log luminance";
  EXPECT_GT(nearEdge, expected - 0.05) << "no halo: the bright side is out of the dark side's base";
  EXPECT_EQ(brightChange, 0.0) << "above mid grey nothing changes";
}

TEST_F(LocalExposureGL, KeepsLocalContrastWithinARegion) {
  // A dark checkerboard of 1-pixel squares one stop apart, 8 stops under mid grey at e = 1.
  const float lo = 0.18f * std::exp2(-8.5f), hi = 2.0f * lo;
  std::vector<glm::vec4> pixels(static_cast<std::size_t>(kW) * kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) pixels[static_cast<std::size_t>(y) * kW + x] = glm::vec4(glm::vec3((x + y) % 2 ? hi : lo), 1.0f);
  const float s = 0.5f;
  const gpu::Image after = adapted(pixels, s, 1.0f);
  double worst = 99.0, best = 0.0, meanLift = 0.0;
  int n = 0;
  for (int y = 20; y < kH - 20; ++y)
    for (int x = 20; x < kW - 21; ++x) {
      const double stops = std::abs(std::log2(luminance(after.at(x + 1, y)) / luminance(after.at(x, y))));
      worst = std::min(worst, stops), best = std::max(best, stops);
      meanLift += liftAt(after, pixels, x, y), ++n;
    }
  meanLift /= n;
  std::printf("[ local   ] a 1-stop checkerboard 8 stops down, s %.1f: lifted %.3f stops on average, neighbours "
              "%.3f to %.3f stops apart after (a global curve of that strength: %.2f)\n",
              s, meanLift, worst, best, 1.0 - s);
  EXPECT_NEAR(meanLift, s * 8.0, 0.1) << "the region's base is its mean log luminance";
  EXPECT_GT(worst, 0.85) << "detail within a region is kept (a global curve would leave 1 - s)";
  EXPECT_LE(best, 1.0 + 1e-4) << "local contrast is never exaggerated";
}

TEST_F(LocalExposureGL, AnAntiAliasedEdgeShowsTheBlendOfWhatItsTwoSidesShow) {
  // The bright orange left (above mid grey: not lifted), 10 stops darker right (lifted), and between
  // them one column of pixels blended as a still's box filter blends an edge, a share α of the bright
  // side (α from 1/16 to 15/16 down the rows). Shown, such a pixel should be the same blend of what
  // the two sides show: α Y_bright + (1 − α) Y_dark g_dark, g_dark the dark side's gain. Sliced at its
  // own luminance the blend was lifted as neither side (the candle's rim: a dark outline between the
  // wax and the lifted table).
  const glm::vec4 bright(1.2f, 0.6f, 0.2f, 1.0f), dark = bright * std::exp2(-10.0f);
  std::vector<glm::vec4> pixels(static_cast<std::size_t>(kW) * kH);
  const int edge = kW / 2;
  auto share = [](int y) { return ((y % 15) + 1) / 16.0f; };
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      glm::vec4 c = x < edge ? bright : x > edge ? dark : share(y) * bright + (1.0f - share(y)) * dark;
      c.a = 1.0f;
      pixels[static_cast<std::size_t>(y) * kW + x] = c;
    }
  const float s = 0.6f, e = 0.5f;
  const gpu::Image after = adapted(pixels, s, e);
  const double gainDark = std::exp2(s * (kGreyStops - std::log2(e * luminance(dark))));
  double worst = 0.0;
  int outside = 0;
  for (int y = 8; y < kH - 8; ++y) {
    const double a = share(y);
    const double expected = a * luminance(bright) + (1.0 - a) * luminance(dark) * gainDark;
    // readTexture's rows run top-down; the upload's row 0 is the texture's bottom.
    const auto shownAt = [&](int x) { return luminance(after.at(x, kH - 1 - y)); };
    const double shown = shownAt(edge);
    worst = std::max(worst, std::abs(shown / expected - 1.0));
    // Never outside what its two sides show.
    const double left = shownAt(edge - 1), right = shownAt(edge + 1);
    outside += shown < std::min(left, right) * (1.0 - 1e-4) || shown > std::max(left, right) * (1.0 + 1e-4);
  }
  std::printf("[ local   ] an anti-aliased edge, 10 stops, s %.1f: the blended column within %.4f of the blend of its "
              "two sides as shown; %d pixels outside them\n", s, worst, outside);
  EXPECT_LT(worst, 0.01) << "a blended pixel shows the blend of what its two sides show";
  EXPECT_EQ(outside, 0) << "no outline darker or brighter than both sides";
}

}  // namespace
}  // namespace tallow
