// Nothing created or deleted per frame (issue 39, point 4): once a scene's passes have made their
// targets, a steady frame — the candle playing, a still accumulating, a directional light over the
// bunny — makes and deletes no GL object (gpu::glObjectTally counts every owner in gpu/gl_objects.h;
// no GL object is created anywhere else: a grep of the sources finds glCreate* in gl_objects.cpp only).
#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include <string>

#include "gpu/gl_objects.h"
#include "gpu/gpu_timer.h"
#include "support/render_support.h"

namespace tallow {
namespace {

/// Frames before a steady one: the GPU timer's ring of query pools fills over its first kRing frames.
constexpr int kSettle = static_cast<int>(gpu::GpuTimer::kRing) + 1;

/// Renders `settle` + `frames` frames of `session` at times t0, t0 + dt, …; returns what the last
/// `frames` created and deleted (empty: nothing).
std::string objectsOfSteadyFrames(test::PresetSession& session, double t0, double dt, int settle, int frames) {
  for (int i = 0; i < settle; ++i) session.renderFrame(t0 + dt * i);
  const gpu::GlObjectTally before = gpu::glObjectTally();
  for (int i = settle; i < settle + frames; ++i) session.renderFrame(t0 + dt * i);
  return gpu::glObjectTally().since(before);
}

int mapsInUse(const test::PresetSession& session) {
  return session.renderer().chosenMapCount(session.scene(), session.settings()).value_or(0);
}

// The default candle (auto K and sizes, history 8, 80 VPLs, the flame) playing at 8 fps, small.
TEST(FrameObjects, TheCandlePlayingCreatesNoGlObjectInASteadyFrame) {
  test::PresetSession s("candle", {"render.width=96", "render.height=54", "field.res=48"});
  for (int i = 0; i < kSettle; ++i) s.renderFrame(10.0 + 0.125 * i);
  const int k = mapsInUse(s);
  const std::string made = objectsOfSteadyFrames(s, 10.0 + 0.125 * kSettle, 0.125, 0, 3);
  ASSERT_EQ(mapsInUse(s), k) << "auto K changed: a reallocation would be due";
  EXPECT_EQ(made, "") << "three frames of the playing candle";
}

// A still: the maps accumulate, the VPLs and shadows hold.
TEST(FrameObjects, AStillAccumulatingCreatesNoGlObject) {
  test::PresetSession s("candle", {"render.width=96", "render.height=54", "field.res=48"});
  EXPECT_EQ(objectsOfSteadyFrames(s, 12.0, 0.0, kSettle, 3), "");
}

// A directional light's shadow map and a mesh: the bunny with its light turning every frame (the
// shadow map, the light G-buffer and the maps redrawn).
TEST(FrameObjects, TheBunnyUnderATurningDirectionalLightCreatesNoGlObject) {
  test::PresetSession s("bunny", {"render.width=96", "render.height=72"});
  const auto turn = [&](int i) {
    s.scene().lights[0].direction = glm::normalize(glm::vec3(-0.75f + 0.05f * float(i), 0.6f, 0.35f));
    s.renderFrame(0.0);
  };
  for (int i = 0; i < kSettle; ++i) turn(i);
  const gpu::GlObjectTally before = gpu::glObjectTally();
  for (int i = kSettle; i < kSettle + 3; ++i) turn(i);
  EXPECT_EQ(gpu::glObjectTally().since(before), "");
}

}  // namespace
}  // namespace tallow
