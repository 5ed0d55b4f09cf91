// Headless renders checked against independent CPU computations of the same scene.
#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include <cmath>

#include "app/config/setup.h"
#include "gpu/readback.h"
#include "gpu/tonemap.h"
#include "support/render_support.h"

namespace tallow {
namespace {

constexpr float kOneLevel = 1.0f / 255.0f;  // one step of an 8-bit display value

// Lambertian sphere (tests/data/lambert_sphere.json): albedo 1 and irradiance π give radiance
// L = (1/π)·π·max(0, n·l) = max(0, n·l), with n the exact sphere normal at the pixel centre.
struct SphereExpectation {
  int width = 128, height = 128;
  float viewHeight = 2.5f;  // orthographic camera height in the preset
  glm::vec3 light = glm::normalize(glm::vec3(1.0f));
  // The GPU draws a 96-ring × 192-segment UV sphere (sss/scene_geometry.cpp). Where the pixel centre
  // lies in the outermost ring of triangles seen from the camera (screen radius within
  // 1 − cos(π/96) of the silhouette, < 0.03 px wide here), the flat triangles and the exact sphere
  // differ in coverage and normal by more than 1/255; those pixels are not compared.
  float silhouetteBand = 1.0f - std::cos(3.14159265f / 96.0f);

  // −1 = pixel in the excluded band; otherwise the expected radiance.
  float expected(int x, int y) const {
    const float u = ((x + 0.5f) / width * 2.0f - 1.0f) * viewHeight * 0.5f * width / height;
    const float v = (1.0f - (y + 0.5f) / height * 2.0f) * viewHeight * 0.5f;
    const float r2 = u * u + v * v;
    const float r = std::sqrt(r2);
    if (r >= 1.0f - silhouetteBand && r <= 1.0f + silhouetteBand) return -1.0f;
    if (r2 >= 1.0f) return 0.0f;  // background
    const glm::vec3 n(u, v, std::sqrt(1.0f - r2));
    return std::max(0.0f, glm::dot(n, light));
  }
};

void expectLambertSphere(const gpu::Image& image, float minCosine) {
  const SphereExpectation sphere;
  ASSERT_EQ(image.width, sphere.width);
  ASSERT_EQ(image.height, sphere.height);
  int compared = 0, excluded = 0, band = 0, lit = 0;
  float worst = 0.0f;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const float e = sphere.expected(x, y);
      if (e < 0.0f || (e > 0.0f && e < minCosine)) {
        ++excluded;
        band += e < 0.0f;
        continue;
      }
      const glm::vec4 p = image.at(x, y);
      for (int c = 0; c < 3; ++c) {
        const float err = std::abs(p[c] - e);
        worst = std::max(worst, err);
        EXPECT_LE(err, kOneLevel) << "pixel (" << x << ", " << y << ") channel " << c << ": " << p[c] << " vs " << e;
        if (err > kOneLevel) return;  // one report is enough
      }
      ++compared;
      lit += e > 0.0f;
    }
  // The silhouette band is a few pixels at most; if many were skipped the test would prove little.
  EXPECT_LT(band, 20);
  EXPECT_EQ(compared + excluded, image.width * image.height);
  EXPECT_GT(lit, 3000);  // about half the disc of radius 51 px is lit
  std::printf("lambert sphere: %d pixels within %.5f (worst %.6f), %d excluded (%d on the silhouette)\n", compared,
              kOneLevel, worst, excluded, band);
}

TEST(RenderGL, LambertSphereMatchesAnalyticShadingWithoutShadows) {
  const auto result = test::renderPreset(test::testScene("lambert_sphere"), {"render.shadows=false"});
  expectLambertSphere(result.image, 0.0f);
}

TEST(RenderGL, ShadowMapDoesNotDarkenTheLitSideOfAConvexSphere) {
  // A convex body never shadows its lit side; away from the terminator (n·l > 0.1, where the
  // shadow map's normal-offset bias is ample) every pixel must still match the analytic value.
  const auto result = test::renderPreset(test::testScene("lambert_sphere"), {"render.shadows=true"});
  expectLambertSphere(result.image, 0.1f);
}

// tests/data/shadow_plate.json: a plate x,z ∈ [−0.5, 0.5], y ∈ [0.99, 1.01] over the ground y = 0,
// light direction l = (2, 1, 0)/√5. A ground point p is shadowed iff p + t·l hits the plate, i.e.
// its shadow is the plate's footprint shifted by −y·(l.x/l.y) = −2y in x: x ∈ [−2.52, −1.48],
// z ∈ [−0.5, 0.5]. Lit ground has L = (1/π)·π·l.y = 1/√5.
struct ShadowPlate {
  int size = 128;
  glm::vec2 centre{-2.0f, 0.0f};
  float viewHeight = 2.0f;
  glm::vec2 shadowMin{-0.5f - 2.0f * 1.01f, -0.5f};
  glm::vec2 shadowMax{0.5f - 2.0f * 0.99f, 0.5f};
  float litRadiance = 1.0f / std::sqrt(5.0f);

  // World (x, z) at a pixel centre. Camera up is −z, so image rows go toward +z.
  glm::vec2 world(int px, int py) const {
    const float s = viewHeight / size;
    return {centre.x + (px + 0.5f) * s - viewHeight * 0.5f, centre.y + (py + 0.5f) * s - viewHeight * 0.5f};
  }
};

TEST(RenderGL, ShadowMapDarkensExactlyTheAnalyticShadow) {
  const auto result = test::renderPreset(test::testScene("shadow_plate"), {"render.pcf_radius=1", "render.shadow_bias=1.5"});
  const ShadowPlate plate;
  // Width of the uncertain border, from the shadow map's resolution: the map is fitted to the
  // casters (planes excluded), i.e. the plate's bounding sphere, radius √(1 + 0.02² + 1)/2 m plus
  // 1 % margin = 0.714 m, over 2048 texels: 0.70 mm texels. PCF radius 1 plus the
  // bilinear comparison blur ±D = 2 texels across the light, which a ground seen at elevation
  // asin(l.y) stretches by 1/l.y = √5; the normal offset of D + 1.5 = 3.5 texels (lights.glsl)
  // lifts the lookup point, which moves the boundary by 3.5·(l.x/l.y) = 7 texels along x.
  const float texel = 2.0f * 0.714f / 2048.0f;
  const float margin = (2.0f * std::sqrt(5.0f) + 7.0f) * texel;
  int inside = 0, outside = 0;
  for (int y = 0; y < plate.size; ++y)
    for (int x = 0; x < plate.size; ++x) {
      const glm::vec2 w = plate.world(x, y);
      const glm::vec4 p = result.image.at(x, y);
      const bool deepInside = w.x > plate.shadowMin.x + margin && w.x < plate.shadowMax.x - margin &&
                              w.y > plate.shadowMin.y + margin && w.y < plate.shadowMax.y - margin;
      const bool clearlyOutside = w.x < plate.shadowMin.x - margin || w.x > plate.shadowMax.x + margin ||
                                  w.y < plate.shadowMin.y - margin || w.y > plate.shadowMax.y + margin;
      if (deepInside) {
        ++inside;
        ASSERT_LE(p.r, kOneLevel) << "shadowed pixel (" << x << ", " << y << ") is lit: " << p.r;
      } else if (clearlyOutside) {
        ++outside;
        ASSERT_NEAR(p.r, plate.litRadiance, kOneLevel) << "lit pixel (" << x << ", " << y << ")";
      }
    }
  // The shadow covers 1.04 m × 1 m of the 2 m × 2 m view: about a quarter of the pixels.
  EXPECT_GT(inside, 3200);
  EXPECT_GT(outside, 9000);
}

// tests/data/point_shadow.json: point light of intensity π at (0, 2, 0), albedo 1, so lit ground
// at (x, 0, z) has L = (1/π)·π·cosθ/d² = 2/d³ with d² = x² + z² + 4. The plate (half-size 0.25,
// top at y = 1.01) throws the central projection |x|,|z| ≤ 0.25·2/(2 − 1.01) = 0.50505; seen from
// above the plate itself hides |x|,|z| < 0.25, so the shadow shows as a ring.
TEST(RenderGL, PointLightCubeShadowMatchesTheCentralProjection) {
  const auto result = test::renderPreset(test::testScene("point_shadow"));
  const float half = 0.25f * 2.0f / (2.0f - 1.01f);
  // Cube faces of 1024² texels (half of render.shadow_map_size) span 90°: 1.5 mrad, i.e. 3.2 mm at
  // the 2.06 m distance of the shadow's edge. PCF ±2 texels, plus the 3.5-texel normal offset
  // (11 mm upward) shifting the edge by 11 mm · 0.25 outward: 2 cm covers all of it.
  const float margin = 0.02f;
  int ring = 0, lit = 0;
  for (int y = 0; y < 128; ++y)
    for (int x = 0; x < 128; ++x) {
      const float wx = (x + 0.5f) / 128.0f * 2.0f - 1.0f;
      const float wz = (y + 0.5f) / 128.0f * 2.0f - 1.0f;
      const float m = std::max(std::abs(wx), std::abs(wz));
      const glm::vec4 p = result.image.at(x, y);
      if (m > 0.25f + margin && m < half - margin) {
        ++ring;
        ASSERT_LE(p.r, kOneLevel) << "pixel (" << x << ", " << y << ") should be in the plate's shadow";
      } else if (m > half + margin) {
        ++lit;
        const float d = std::sqrt(wx * wx + wz * wz + 4.0f);
        ASSERT_NEAR(p.r, 2.0f / (d * d * d), kOneLevel) << "pixel (" << x << ", " << y << ")";
      }
    }
  EXPECT_GT(ring, 2500);  // ((0.505 − 0.02)² − (0.25 + 0.02)²)·4 m² of 4 m² × 128²: ~2,660 px
  EXPECT_GT(lit, 11000);
  bool ranPointPass = false;
  for (const auto& pass : result.timings.passes) ranPointPass |= pass.name == "shadow.point";
  EXPECT_TRUE(ranPointPass);
}

TEST(RenderGL, WithShadowsOffTheSameGroundIsLitEverywhere) {
  const auto result = test::renderPreset(test::testScene("shadow_plate"), {"render.shadows=false"});
  const ShadowPlate plate;
  for (int y = 0; y < plate.size; ++y)
    for (int x = 0; x < plate.size; ++x) ASSERT_NEAR(result.image.at(x, y).r, plate.litRadiance, kOneLevel);
}

}  // namespace
}  // namespace tallow

namespace tallow {
namespace {

// The window's tone mapping (shaders/display.frag) and the PNG writer's (gpu/tonemap.cpp) compile
// the same shaders/common/tonemap.glsl; on the same radiance they must agree to the 8-bit level.
TEST(RenderGL, DisplayPassMatchesTheCppToneMapOfThePngWriter) {
  for (const char* op : {"clamp", "reinhard", "aces", "hue-preserving"}) {
    app::SceneOptions options;
    options.preset = "bunny";
    options.sets = {"render.width=160", "render.height=90", std::string("render.tonemap=") + op,
                    "render.exposure_ev=1.5"};
    const app::LoadedScene loaded = app::loadScene(options);
    gpu::ContextOptions contextOptions;
    auto context = gpu::GlContext::create(contextOptions);
    const gpu::ShaderLibrary shaders;  // outlives the renderer, which keeps a reference
    sss::Renderer renderer(shaders, loaded.config.scene, loaded.config.render);
    renderer.render(loaded.config.scene, loaded.config.render, 0.0);
    const gpu::Image radiance = renderer.readRadiance();

    gpu::Texture display = gpu::Texture::create2D(GL_RGBA8, 160, 90);
    gpu::Framebuffer fb;
    fb.attachColor(0, display);
    fb.setDrawBuffers(1);
    fb.checkComplete("test display target");
    renderer.display(fb.id(), 160, 90, loaded.config.render.toneMap);
    const gpu::Image shown = gpu::readColor(fb, 0, 160, 90);

    int worst = 0;
    for (int y = 0; y < 90; ++y)
      for (int x = 0; x < 160; ++x) {
        const glm::vec3 cpu = gpu::toneMapToSrgb(glm::vec3(radiance.at(x, y)), loaded.config.render.toneMap);
        for (int c = 0; c < 3; ++c)
          worst = std::max(worst, std::abs(static_cast<int>(std::lround(cpu[c] * 255.0f)) -
                                           static_cast<int>(std::lround(shown.at(x, y)[c] * 255.0f))));
      }
    EXPECT_LE(worst, 1) << op;  // float rounding may differ by one level between GPU and CPU
  }
}

}  // namespace
}  // namespace tallow
