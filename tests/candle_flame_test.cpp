// The candle's flame without GL (issue 35, point 4): the blackbody its colour comes from, against the
// CIE's illuminant A; its flicker, deterministic in t; the point light that stands in for it.
#include "geometry/candle_flame.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "sss/field_source.h"

namespace tallow {
namespace {

/// Linear sRGB (Rec. 709, D65) to CIE xy chromaticity: IEC 61966-2-1's matrix, the inverse of the
/// one shaders/flame/blackbody.glsl applies.
glm::dvec2 chromaticity(glm::dvec3 rgb) {
  const double x = 0.4124 * rgb.x + 0.3576 * rgb.y + 0.1805 * rgb.z;
  const double y = 0.2126 * rgb.x + 0.7152 * rgb.y + 0.0722 * rgb.z;
  const double z = 0.0193 * rgb.x + 0.1192 * rgb.y + 0.9505 * rgb.z;
  return {x / (x + y + z), y / (x + y + z)};
}

TEST(Blackbody, IlluminantAIsTheBlackbodyAt2856K) {
  // CIE illuminant A is a blackbody at 2856 K, chromaticity (0.44757, 0.40745) (CIE 15:2004). The
  // fitted colour-matching functions (Wyman et al. 2013) and a 5 nm sum stay within 0.003 of it.
  const glm::dvec3 rgb = geometry::blackbodyColour(2856.0);
  const glm::dvec2 xy = chromaticity(rgb);
  EXPECT_NEAR(xy.x, 0.44757, 0.003);
  EXPECT_NEAR(xy.y, 0.40745, 0.003);
  EXPECT_NEAR(0.2126 * rgb.x + 0.7152 * rgb.y + 0.0722 * rgb.z, 1.0, 1e-9) << "luminance 1";
  // Hotter is bluer, cooler redder; a candle's 1850 K is orange: red over green over blue.
  const glm::dvec3 candle = geometry::blackbodyColour(1850.0), hot = geometry::blackbodyColour(6500.0);
  EXPECT_GT(candle.x, candle.y);
  EXPECT_GT(candle.y, candle.z);
  EXPECT_GT(hot.z / hot.x, candle.z / candle.x);
  // Its hue as a display shows it (HSV of the sRGB-encoded colour): about 30° (issue 36: amber).
  const auto encode = [](double c) { return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055; };
  const double top = std::max({candle.x, candle.y, candle.z});
  const glm::dvec3 shown(encode(candle.x / top), encode(candle.y / top), encode(candle.z / top));
  const double hue = 60.0 * (shown.y - shown.z) / (shown.x - std::min(shown.y, shown.z));
  std::printf("[ flame   ] 1850 K: linear sRGB (%.3f, %.3f, %.3f), displayed hue %.1f°\n", candle.x, candle.y, candle.z, hue);
  EXPECT_NEAR(hue, 30.0, 5.0);
}

TEST(CandleFlame, FlickersDeterministicallyAndTheLightFollowsIt) {
  // The bar: over half a second the light's intensity varies by at least 1% or its position
  // sways at least 0.1 mm off its burn-down line, with flame.flicker 1; with 0 neither.
  sss::Scene scene;
  sss::SceneObject candle;
  candle.name = "candle";
  candle.shape = sss::ShapeKind::Field;
  candle.field.kind = sss::FieldKind::Candle;
  scene.objects.push_back(candle);
  sss::Light light;
  light.kind = sss::LightKind::Point;
  light.follow = 0;
  light.intensity = glm::vec3(0.006f);
  scene.lights.push_back(light);
  const auto range = [&](double flicker) {
    scene.flameFlicker = static_cast<float>(flicker);
    double lo = 1e30, hi = 0.0, sway = 0.0;
    for (int i = 0; i <= 50; ++i) {
      const double t = 12.0 + 0.01 * i;
      const sss::Light l = sss::sceneAtTime(scene, t).lights[0];
      const double y = 0.2126 * l.intensity.x + 0.7152 * l.intensity.y + 0.0722 * l.intensity.z;
      lo = std::min(lo, y);
      hi = std::max(hi, y);
      sway = std::max(sway, std::hypot(double(l.position.x), double(l.position.z)));
      // The same t twice: the same light.
      EXPECT_EQ(l.position, sss::sceneAtTime(scene, t).lights[0].position);
    }
    return std::pair{hi / lo - 1.0, sway};
  };
  const auto [variation, sway] = range(1.0);
  std::printf("[ flame   ] flicker 1: intensity varies %.2f%%, sways %.3f mm off the axis over 0.5 s\n",
              100.0 * variation, sway * 1e3);
  EXPECT_GE(variation, 0.01);
  EXPECT_GE(sway, 0.0001);
  const auto [steady, still] = range(0.0);
  EXPECT_LT(steady, 1e-6);
  EXPECT_LT(still, 1e-7);
  // The light's luminance is the preset's, its colour the flame's: red over green over blue.
  scene.flameFlicker = 0.0f;
  const sss::Light l = sss::sceneAtTime(scene, 12.0).lights[0];
  EXPECT_NEAR(0.2126 * l.intensity.x + 0.7152 * l.intensity.y + 0.0722 * l.intensity.z, 0.006, 1e-8);
  EXPECT_GT(l.intensity.x, l.intensity.y);
  EXPECT_GT(l.intensity.y, l.intensity.z);
  // It stands at the flame's emission centre: the nominal flame point of the field (wick tip +
  // flameLift), within half a millimetre.
  const geometry::CandleField field(12.0);
  std::printf("[ flame   ] t = 12 s: light at y = %.2f mm, the field's flame point %.2f mm\n", l.position.y * 1e3,
              field.flamePosition().y * 1e3);
  EXPECT_NEAR(l.position.y, field.flamePosition().y, 0.0005);
}

}  // namespace
}  // namespace tallow
