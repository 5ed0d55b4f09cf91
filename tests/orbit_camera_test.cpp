// The view window's mouse camera (app/playback/orbit_camera.h) against closed-form positions.
#include "app/playback/orbit_camera.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>

#include <cmath>

namespace tallow::app {
namespace {

// Float storage of the camera (sss::Camera): results agree with the exact values to a few ulps of
// the coordinates (≈ 1e-7 relative); 1e-5 m on metre-sized scenes leaves room and catches any error
// of the geometry, which would be of the order of the step.
constexpr float kTolerance = 1e-5f;

void expectNear(const glm::vec3& a, const glm::vec3& b, const char* what) {
  EXPECT_NEAR(a.x, b.x, kTolerance) << what;
  EXPECT_NEAR(a.y, b.y, kTolerance) << what;
  EXPECT_NEAR(a.z, b.z, kTolerance) << what;
}

sss::Camera frontCamera() {
  sss::Camera c;
  c.position = {0.0f, 0.0f, 2.0f};
  c.target = {0.0f, 0.0f, 0.0f};
  c.up = {0.0f, 1.0f, 0.0f};
  c.fovYDeg = 90.0f;
  return c;
}

TEST(OrbitCamera, YawTurnsAboutTheUpAxis) {
  sss::Camera c = frontCamera();
  orbitCamera(c, glm::half_pi<double>(), 0.0);
  // (0, 0, 2) turned by +90° about +y (counter-clockwise seen from above) is (2, 0, 0).
  expectNear(c.position, {2.0f, 0.0f, 0.0f}, "quarter turn");
  for (int i = 0; i < 3; ++i) orbitCamera(c, glm::half_pi<double>(), 0.0);
  expectNear(c.position, {0.0f, 0.0f, 2.0f}, "full turn");
  expectNear(c.target, {0.0f, 0.0f, 0.0f}, "target stays");
}

TEST(OrbitCamera, PitchRisesAndStopsShortOfThePole) {
  sss::Camera c = frontCamera();
  orbitCamera(c, 0.0, glm::radians(30.0));
  // 30° above the horizon at distance 2: (0, 2 sin 30°, 2 cos 30°).
  expectNear(c.position, {0.0f, 1.0f, std::sqrt(3.0f)}, "30 degrees up");
  orbitCamera(c, 0.0, glm::radians(120.0));  // would pass over the top
  const glm::vec3 d = glm::normalize(c.position - c.target);
  EXPECT_NEAR(std::acos(d.y), glm::radians(kPitchMarginDeg), 1e-5) << "stopped kPitchMarginDeg from the pole";
  EXPECT_NEAR(glm::length(c.position - c.target), 2.0f, kTolerance) << "distance kept";
  EXPECT_GT(d.z, 0.0f) << "still on the side it started from";
}

TEST(OrbitCamera, PanMovesBothByViewHeights) {
  sss::Camera c = frontCamera();
  // 90° field of view at distance 2: the view is 2 · 2 · tan 45° = 4 m high at the target.
  EXPECT_NEAR(viewHeightAtTarget(c), 4.0, 1e-6);
  panCamera(c, 0.25, -0.5);
  // The scene follows the mouse: the camera moves left 1 m and up 2 m (right is +x, up is +y here).
  expectNear(c.target, {-1.0f, 2.0f, 0.0f}, "target");
  expectNear(c.position, {-1.0f, 2.0f, 2.0f}, "position");
}

TEST(OrbitCamera, ZoomScalesTheDistanceOrTheHeight) {
  sss::Camera c = frontCamera();
  zoomCamera(c, 0.5);
  expectNear(c.position, {0.0f, 0.0f, 1.0f}, "half the distance");
  zoomCamera(c, 1e-9);
  EXPECT_NEAR(glm::length(c.position - c.target), kMinDistance, 1e-7) << "never reaches the target";
  sss::Camera ortho = frontCamera();
  ortho.orthographic = true;
  ortho.orthoHeight = 0.4f;
  zoomCamera(ortho, 2.0);
  EXPECT_FLOAT_EQ(ortho.orthoHeight, 0.8f);
  expectNear(ortho.position, {0.0f, 0.0f, 2.0f}, "an orthographic camera zooms by its height");
}

}  // namespace
}  // namespace tallow::app
