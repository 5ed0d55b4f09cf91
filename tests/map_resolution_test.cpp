// sss.map_size=auto and sss.light_map_size=auto (sss/maps/map_resolution.h, issue 17 point 4): the
// sphere's size on screen against a projection by glm, the sizes against the rule's bounds worked by
// hand for the bunny at 0.01 and 1 m, and every choice a power of two that meets both bounds.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>
#include <random>

#include "sss/maps/map_resolution.h"

namespace tallow {
namespace {

using sss::autoLightMapSize;
using sss::autoMapSize;

// Blue marble's 1/σ_tr (Jensen et al. 2001: σ_a 0.0071, σ_s' 3.00 mm⁻¹): 1/√(3·0.0071·3.0071) mm.
const double kMarbleBlueMm = 1.0 / std::sqrt(3.0 * 0.0071 * (0.0071 + 3.0));

TEST(MapResolution, ProjectedDiameterMatchesAPerspectiveProjection) {
  // A sphere off the view axis: its extent across the screen's vertical, projected by glm.
  sss::Camera camera;
  camera.position = {0.3f, 0.2f, 2.0f};
  camera.target = {0.0f, 0.0f, 0.0f};
  camera.fovYDeg = 40.0f;
  const sss::BoundingSphere sphere{{0.05f, -0.02f, 0.1f}, 0.12f};
  const int height = 480;
  const glm::mat4 view = glm::lookAt(camera.position, camera.target, camera.up);
  const glm::mat4 proj = glm::perspective(glm::radians(camera.fovYDeg), 4.0f / 3.0f, 0.01f, 100.0f);
  // Two points a diameter apart, perpendicular to the line of sight through the centre, along the
  // camera's up: their distance in pixels is the sphere's diameter at its centre's depth.
  const glm::vec3 toCentre = glm::normalize(sphere.centre - camera.position);
  const glm::vec3 side = glm::normalize(glm::cross(toCentre, camera.up));
  const glm::vec3 up = glm::cross(side, toCentre);
  const auto pixelY = [&](glm::vec3 p) {
    const glm::vec4 c = proj * view * glm::vec4(p, 1.0f);
    return (c.y / c.w) * 0.5 * height;
  };
  const auto pixelX = [&](glm::vec3 p) {
    const glm::vec4 c = proj * view * glm::vec4(p, 1.0f);
    return (c.x / c.w) * 0.5 * height * (4.0 / 3.0);
  };
  const glm::vec3 a = sphere.centre + sphere.radius * up, b = sphere.centre - sphere.radius * up;
  const double glmPixels = std::hypot(pixelX(a) - pixelX(b), pixelY(a) - pixelY(b));
  EXPECT_NEAR(sss::projectedDiameterPixels(camera, height, sphere), glmPixels, 0.02 * glmPixels);

  camera.orthographic = true;
  camera.orthoHeight = 0.6f;
  EXPECT_NEAR(sss::projectedDiameterPixels(camera, height, sphere), 0.24 / 0.6 * 480, 1e-3);
  // A camera inside the sphere sees it span at least the whole image.
  camera.orthographic = false;
  camera.position = sphere.centre;
  EXPECT_GE(sss::projectedDiameterPixels(camera, height, sphere), height);
}

TEST(MapResolution, TheBunnyAtOneCentimetreAndOneMetre) {
  // 0.01 m: a 14 mm sphere, 80 px on screen, 1/σ_tr 4 mm: the screen decides, two texels a pixel.
  EXPECT_EQ(autoMapSize(14.0, kMarbleBlueMm, 80.0, 16384), 256);
  EXPECT_EQ(autoMapSize(14.0, kMarbleBlueMm, 30.0, 16384), 128) << "the floor";
  // 1 m: 1400 mm / 3.95 mm = 354 texels across for the diffusion length, 60 px on screen: 512.
  EXPECT_EQ(autoMapSize(1400.0, kMarbleBlueMm, 60.0, 16384), 512);
  // The same bunny filling a 1080p screen: the screen asks for at most 512.
  EXPECT_EQ(autoMapSize(1400.0, kMarbleBlueMm, 800.0, 16384), 512);
  EXPECT_EQ(autoMapSize(140.0, kMarbleBlueMm, 800.0, 16384), 512);
  // 5 m of marble: 7000 / 3.95 mm = 1772 texels for the diffusion length → 2048, the cap.
  EXPECT_EQ(autoMapSize(7000.0, kMarbleBlueMm, 60.0, 16384), 2048);
  EXPECT_EQ(autoMapSize(70000.0, kMarbleBlueMm, 60.0, 16384), 2048);
  EXPECT_EQ(autoMapSize(7000.0, kMarbleBlueMm, 60.0, 1024), 1024) << "the GPU's texture limit";
  // Light G-buffers: 4 × 1400 / 3.95 = 1417 → 2048 for a directional light, 1024 for a point light's
  // cube; the 0.1 m bunny keeps the paper's 512.
  EXPECT_EQ(autoLightMapSize(1400.0, kMarbleBlueMm, false, 16384), 2048);
  EXPECT_EQ(autoLightMapSize(1400.0, kMarbleBlueMm, true, 16384), 1024);
  EXPECT_EQ(autoLightMapSize(140.0, kMarbleBlueMm, false, 16384), 512);
  EXPECT_EQ(autoLightMapSize(14000.0, kMarbleBlueMm, false, 16384), 4096);
}

TEST(MapResolution, EveryChoiceIsAPowerOfTwoMeetingBothBoundsOrAtTheCap) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> logUniform(-3.0, 4.0);
  for (int i = 0; i < 2000; ++i) {
    const double diameter = std::pow(10.0, logUniform(rng)), diffusion = std::pow(10.0, logUniform(rng) - 1.0);
    const double pixels = std::pow(10.0, 0.5 * logUniform(rng) + 1.5);
    const int size = autoMapSize(diameter, diffusion, pixels, 8192);
    ASSERT_EQ(size & (size - 1), 0) << size;
    ASSERT_GE(size, sss::kAutoMapMin);
    ASSERT_LE(size, sss::kAutoMapMax);
    const double need = std::max(std::min(2.0 * pixels, 512.0), diameter / diffusion);
    if (size < sss::kAutoMapMax) {
      ASSERT_GE(size, need) << "a texel no wider than half a pixel or 1/σ_tr";
    }
    if (size > sss::kAutoMapMin) {
      ASSERT_LT(size / 2, need) << "and no finer than that";
    }
  }
}

TEST(MapResolution, AlgorithmOneFiltersOverAtMostHalfADiffusionLength) {
  // A map spans the views' sphere's diameter; 4 mm in a 1 m span is 0.004 of it, half of that 0.002.
  EXPECT_FLOAT_EQ(sss::maxMapFootprint(4.0, 0.5f), 0.002f);
  EXPECT_FLOAT_EQ(sss::maxMapFootprint(4.0, 0.005f), 0.2f);
}

}  // namespace
}  // namespace tallow
