// The point lights' shadow look-up (common/cube_shadow_depth.glsl) against the depth the
// rasteriser writes through cubeFaceViewProjections: the receivers' reference must be the same
// number, or every receiver would be shadowed or lit by the difference.
#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include "gpu/glsl_shared.h"
#include "sss/view_setup.h"

namespace tallow::glsl {
#include "shaders/common/cube_shadow_depth.glsl"
}  // namespace tallow::glsl

namespace {

/// The face GL's cube look-up picks for direction d (largest |component|, Table 8.19's order).
int cubeFace(const glm::vec3& d) {
  const glm::vec3 a = glm::abs(d);
  if (a.x >= a.y && a.x >= a.z) return d.x > 0 ? 0 : 1;
  if (a.y >= a.z) return d.y > 0 ? 2 : 3;
  return d.z > 0 ? 4 : 5;
}

/// Window depth of the light's offset d in its face's projection (GL's default depth range), as the
/// shadow pass computes it: float matrices about the light (shaders/shadow_depth.vert).
double rasterDepth(float range, const glm::vec3& d) {
  const auto faces =
      tallow::sss::cubeFaceViewProjections(glm::vec3(0.0f), range * tallow::glsl::kCubeShadowNearFraction, range);
  const glm::vec4 clip = faces[static_cast<std::size_t>(cubeFace(d))] * glm::vec4(d, 1.0f);
  return 0.5 * double(clip.z) / double(clip.w) + 0.5;
}

TEST(CubeShadowDepth, IsTheDepthTheFacesProjectionWrites) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const glm::vec3 light(0.3f, 1.2f, -0.4f);
  for (float range : {0.05f, 1.0f, 3.0f, 40.0f})
    for (int i = 0; i < 2000; ++i) {
      const glm::vec3 d = glm::vec3(u(rng), u(rng), u(rng)) * (range / std::sqrt(3.0f));
      if (glm::length(d) < 0.01f * range) continue;  // beyond the near plane only
      const glm::vec3 offset = (light + d) - light;  // as both the pass and the receivers take it
      const double expected = rasterDepth(range, offset);
      const float got = tallow::glsl::cubeShadowDepth(offset, range);
      // A few float steps near 1 (1.2e-7 each): well inside one texel of normal offset (≥ 13 steps
      // at the far plane for 1024² faces, OneTexelOfOffsetIsResolvedAtTheFarPlane).
      ASSERT_NEAR(got, expected, 4.8e-7) << "range " << range << " offset " << d.x << " " << d.y << " " << d.z;
      ASSERT_GT(got, 0.0f);
      ASSERT_LE(got, 1.0f);
    }
}

// Along one ray the depth grows with distance, and the normal offset of one texel (the least the
// receivers add, common/lights.glsl) moves it by several of float's steps near 1, so the
// comparison resolves it even at the far plane: d(depth) ≈ n·θm/m² = 1e-3·θ·range/m, 6.5 steps for
// 2048² faces at the far plane whatever the range (13 for the default 1024² faces).
TEST(CubeShadowDepth, OneTexelOfOffsetIsResolvedAtTheFarPlane) {
  const float range = 10.0f;
  const float texelAngle = 1.5707964f / 2048.0f;  // the largest cube face render.shadow_map_size allows here
  const glm::vec3 dir = glm::normalize(glm::vec3(1.0f, 0.3f, -0.2f));
  const float far = range / 1.01f;
  const float step = texelAngle * far;
  const float a = tallow::glsl::cubeShadowDepth(dir * (far - step), range);
  const float b = tallow::glsl::cubeShadowDepth(dir * far, range);
  EXPECT_LT(a, b);
  EXPECT_GT(b - a, 5.0f * (std::nextafter(1.0f, 2.0f) - 1.0f));
}

}  // namespace

namespace {

TEST(CubeShadowDepth, TheAxisDistanceInvertsTheStoredDepth) {
  // method=burley reads the first surface's distance back from the stored depth: the rasteriser's
  // depth of an offset (rasterDepth, through the face's projection) gives back its largest axis
  // component, to float precision of the depth (relative 1e-4 at the far end of the range).
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (const float range : {0.5f, 4.0f, 60.0f})
    for (int i = 0; i < 200; ++i) {
      glm::vec3 d(u(rng), u(rng), u(rng));
      if (glm::length(d) < 1e-3f) continue;
      d *= range * 0.9f / std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)}) * (0.02f + 0.98f * std::abs(u(rng)));
      const float m = std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)});
      const float z = static_cast<float>(rasterDepth(range, d));
      EXPECT_NEAR(tallow::glsl::cubeShadowAxisDistance(z, range), m, 1e-4f * range) << "range " << range;
    }
}

}  // namespace
