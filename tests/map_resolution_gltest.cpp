// sss.map_size=auto and sss.light_map_size=auto in the renderer (issue 17, point 4): the marble
// bunny at 1 m, where the diffusion length decides, and at 0.01 m, where the floors do (worked out
// in tests/map_resolution_test.cpp from its size and blue marble's 1/σ_tr); the choice made at a
// restart and kept while the maps accumulate, however the camera moves.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "sss/maps/map_resolution.h"
#include "sss/maps/radiosity_maps.h"
#include "support/render_support.h"

namespace tallow {
namespace {

std::vector<std::string> bunnyAt(double scale) {
  const double f = scale / 0.1;  // the preset's camera, moved with the bunny (scripts/results_auto.py)
  return {"scale=" + std::to_string(scale),
          "camera.position=" + std::to_string(0.05 * f) + "," + std::to_string(0.13 * f) + "," + std::to_string(0.32 * f),
          "camera.target=0," + std::to_string(0.045 * f) + ",0",
          "render.width=32", "render.height=24", "sss.maps=2", "sss.samples=1", "sss.frames=4",
          "render.shadow_map_size=64", "sss.map_size=auto", "sss.light_map_size=auto"};
}

TEST(MapResolutionRenderer, TheOneMetreBunnyGetsItsSizesFromTheDiffusionLength) {
  // The bunny 1 m across has a bounding sphere between 1012 and 2024 mm (its box's diagonal):
  // 256 < D / 3.95 mm ≤ 512 and 1024 < 4 D / 3.95 mm ≤ 2048, whatever the 24-pixel screen says.
  test::PresetSession session("bunny", bunnyAt(1.0));
  session.render(0.0);
  const sss::RadiosityMaps* maps = session.renderer().module<sss::RadiosityMaps>();
  ASSERT_NE(maps, nullptr);
  const double diameterMm = 2000.0 * maps->sphere().radius;
  ASSERT_GT(diameterMm, 1012.0);
  ASSERT_LE(diameterMm, 2024.0);
  EXPECT_EQ(maps->mapSize(), 512);
  EXPECT_EQ(maps->lightMapSize(), 2048);
  EXPECT_EQ(maps->maps().width(), 512) << "the maps are allocated at the chosen size";
}

TEST(MapResolutionRenderer, TheCentimetreBunnyGetsTheFloorsAndKeepsThemWhileTheCameraMoves) {
  test::PresetSession session("bunny", bunnyAt(0.01));
  session.render(0.0);
  const sss::RadiosityMaps* maps = session.renderer().module<sss::RadiosityMaps>();
  ASSERT_NE(maps, nullptr);
  EXPECT_EQ(maps->mapSize(), sss::kAutoMapMin);
  EXPECT_EQ(maps->lightMapSize(), sss::kAutoLightMin);
  EXPECT_EQ(maps->frames(), 1);

  // Ten times closer on a 400-pixel-tall image, the screen would want larger maps; but neither the
  // camera nor the image size is an input of the maps: they go on accumulating at their size.
  sss::Camera& camera = session.scene().camera;
  camera.position = camera.target + 0.1f * (camera.position - camera.target);
  session.settings().height = 400;
  const int wanted = sss::autoMapSize(2000.0 * maps->sphere().radius, 1.0 / std::sqrt(3.0 * 0.0071 * 3.0071),
                                      sss::projectedDiameterPixels(camera, 400, maps->sphere()), 1 << 14);
  ASSERT_GT(wanted, sss::kAutoMapMin);
  session.render(0.0);
  EXPECT_EQ(maps->frames(), 2);
  EXPECT_EQ(maps->mapSize(), sss::kAutoMapMin);

  // A restart chooses again, from the camera and image it then has.
  session.renderer().restartAccumulation();
  session.render(0.0);
  EXPECT_EQ(maps->frames(), 1);
  EXPECT_EQ(maps->mapSize(), wanted);
  EXPECT_EQ(maps->maps().width(), wanted);
}

}  // namespace
}  // namespace tallow
