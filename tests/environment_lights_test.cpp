// An environment map as M directional lights (sss/environment_lights): median cut on constant and
// one-pixel maps, the power centroid, the mapping convention and the shipped env.hdr.
#include "sss/maps/environment_lights.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>

#include "app/config/input_error.h"
#include "app/config/preset.h"
#include "gpu/hdr_io.h"

namespace tallow::sss {
namespace {

constexpr double kPi = std::numbers::pi;

gpu::Image constantMap(int w, int h, float l) {
  gpu::Image img(w, h);
  for (glm::vec4& p : img.pixels) p = glm::vec4(l, l, l, 1.0f);
  return img;
}

glm::dvec3 pixelDirection(const gpu::Image& m, double x, double y, double rot = 0.0) {
  return environmentDirection(x / m.width, y / m.height, rot);
}

double angleBetween(glm::dvec3 a, glm::dvec3 b) {
  return std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0, 1.0));
}

TEST(EnvironmentLights, MappingConvention) {
  auto near = [](glm::dvec3 a, glm::dvec3 b) { return glm::length(a - b) < 1e-12; };
  EXPECT_TRUE(near(environmentDirection(0.5, 0.0, 0.0), {0, 1, 0}));   // row 0: zenith
  EXPECT_TRUE(near(environmentDirection(0.5, 1.0, 0.0), {0, -1, 0}));  // last row: nadir
  EXPECT_TRUE(near(environmentDirection(0.5, 0.5, 0.0), {0, 0, -1}));  // centre: −z
  EXPECT_TRUE(near(environmentDirection(0.75, 0.5, 0.0), {1, 0, 0}));
  EXPECT_TRUE(near(environmentDirection(0.25, 0.5, 0.0), {-1, 0, 0}));
  EXPECT_TRUE(near(environmentDirection(0.0, 0.5, 0.0), {0, 0, 1}));
  // +90° about +y, counter-clockwise from above: +x → −z, −z → −x.
  EXPECT_TRUE(near(environmentDirection(0.75, 0.5, 90.0), {0, 0, -1}));
  EXPECT_TRUE(near(environmentDirection(0.5, 0.5, 90.0), {-1, 0, 0}));
}

// A constant map L: the lights' irradiances sum to ∫ L dω = 4πL (the pixel solid angles are exact),
// and the irradiance they give an upward plane, Σ E_i max(0, d_i·y), tends to ∫ L max(0, ω·y) dω
// = πL. Bound: for a light of region R, |E_i max(0, d_i·y) − ∫_R L max(0, ω·y) dω| ≤ E_i · max over
// ω ∈ R of |d_i − ω| (max(0, ·) is 1-Lipschitz and |y| = 1), so the total error is at most
// Σ E_i · r_i, r_i the largest chord from d_i to the region, measured here over the region's pixel
// corners plus one pixel diagonal. With 4πL/M per light and r_i shrinking like 1/√M the error is
// O(L/√M); the test checks it against the bound and that it shrinks from M = 16 to M = 256.
TEST(EnvironmentLights, ConstantMapTotalsAndUpwardIrradiance) {
  const float L = 0.7f;
  const gpu::Image map = constantMap(128, 64, L);
  double previousError = 1e30;
  for (int m : {16, 64, 256}) {
    const std::vector<EnvironmentLight> lights = medianCutEnvironment(map, m, 0.0);
    ASSERT_EQ(lights.size(), static_cast<std::size_t>(m));
    double total = 0.0, upward = 0.0, bound = 0.0;
    const double pixelChord = std::hypot(2.0 * kPi / map.width, kPi / map.height);
    for (const EnvironmentLight& l : lights) {
      EXPECT_NEAR(glm::length(glm::dvec3(l.direction)), 1.0, 1e-6);
      EXPECT_FLOAT_EQ(l.irradiance.r, l.irradiance.g);
      total += l.irradiance.r;
      upward += l.irradiance.r * std::max(0.0, static_cast<double>(l.direction.y));
      double chord = 0.0;
      for (int y = l.region.y; y <= l.region.w; ++y)
        for (int x = l.region.x; x <= l.region.z; ++x)
          chord = std::max(chord, glm::length(glm::dvec3(l.direction) - pixelDirection(map, x, y)));
      bound += l.irradiance.r * (chord + pixelChord);
      // Equal power: each region holds 4πL/M to within a row or column of pixels.
      EXPECT_NEAR(l.irradiance.r, 4.0 * kPi * L / m, 4.0 * kPi * L / m * 0.35) << "M = " << m;
    }
    EXPECT_NEAR(total, 4.0 * kPi * L, 1e-5 * 4.0 * kPi * L) << "M = " << m;
    const double error = std::abs(upward - kPi * L);
    EXPECT_LE(error, bound) << "M = " << m;
    EXPECT_LT(error, 0.1 * kPi * L) << "M = " << m;
    EXPECT_LT(error, previousError * 1.01) << "M = " << m;
    previousError = error;
  }
}

TEST(EnvironmentLights, OneBrightPixelGivesALightTowardIt) {
  gpu::Image map = constantMap(64, 32, 0.001f);
  const int bx = 41, by = 9;
  map.at(bx, by) = glm::vec4(5000.0f, 4000.0f, 3000.0f, 1.0f);
  for (double rot : {0.0, 37.0}) {
    const std::vector<EnvironmentLight> lights = medianCutEnvironment(map, 16, rot);
    ASSERT_FALSE(lights.empty());
    const auto brightest = std::max_element(lights.begin(), lights.end(), [](const auto& a, const auto& b) {
      return a.irradiance.r < b.irradiance.r;
    });
    const glm::dvec3 expected = pixelDirection(map, bx + 0.5, by + 0.5, rot);
    // The region around the pixel may hold a little of the dim background too.
    EXPECT_LT(angleBetween(glm::dvec3(brightest->direction), expected), 0.02) << "rotation " << rot;
    EXPECT_GE(brightest->region.x, 0);
    EXPECT_TRUE(bx >= brightest->region.x && bx < brightest->region.z && by >= brightest->region.y &&
                by < brightest->region.w);
  }
  // Without any background the pixel is the only region with power: one light, exactly toward it.
  gpu::Image lone = constantMap(64, 32, 0.0f);
  lone.at(bx, by) = glm::vec4(2.0f);
  const std::vector<EnvironmentLight> one = medianCutEnvironment(lone, 16, 0.0);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_LT(angleBetween(glm::dvec3(one[0].direction), pixelDirection(lone, bx + 0.5, by + 0.5)), 1e-6);
  const double dOmega = (2.0 * kPi / 64) * (std::cos(kPi * by / 32) - std::cos(kPi * (by + 1) / 32));
  EXPECT_NEAR(one[0].irradiance.g, 2.0 * dOmega, 1e-6 * dOmega);
}

TEST(EnvironmentLights, OneLightIsThePowerCentroid) {
  gpu::Image map = constantMap(32, 16, 0.0f);
  map.at(3, 4) = glm::vec4(1.0f, 1.0f, 1.0f, 1.0f);
  map.at(20, 11) = glm::vec4(0.0f, 3.0f, 0.0f, 1.0f);  // luminance 0.7152 · 3
  const std::vector<EnvironmentLight> lights = medianCutEnvironment(map, 1, 0.0);
  ASSERT_EQ(lights.size(), 1u);
  auto dOmega = [&](int y) { return (2.0 * kPi / 32) * (std::cos(kPi * y / 16) - std::cos(kPi * (y + 1) / 16)); };
  const glm::dvec3 centroid = 1.0 * dOmega(4) * pixelDirection(map, 3.5, 4.5) +
                              0.7152 * 3.0 * dOmega(11) * pixelDirection(map, 20.5, 11.5);
  EXPECT_LT(angleBetween(glm::dvec3(lights[0].direction), centroid), 1e-6);
  EXPECT_NEAR(lights[0].irradiance.r, dOmega(4), 1e-7);
  EXPECT_NEAR(lights[0].irradiance.g, dOmega(4) + 3.0 * dOmega(11), 1e-6);
  EXPECT_NEAR(lights[0].solidAngle, 4.0 * kPi, 1e-9);
  // A uniform map has no centroid (Σ ω dω = 0): the light still carries 4πL.
  const std::vector<EnvironmentLight> uniform = medianCutEnvironment(constantMap(16, 8, 1.0f), 1, 0.0);
  ASSERT_EQ(uniform.size(), 1u);
  EXPECT_NEAR(uniform[0].irradiance.b, 4.0 * kPi, 1e-5);
}

TEST(EnvironmentLights, ScaleShadowsAndBadInput) {
  gpu::Image map = constantMap(64, 32, 1.0f);
  Environment env;
  env.lights = 8;
  env.scale = 2.0f;
  const std::vector<Light> lights = environmentLights(map, env);
  ASSERT_EQ(lights.size(), 8u);
  double total = 0.0;
  int shadows = 0;
  for (const Light& l : lights) {
    EXPECT_EQ(l.kind, LightKind::Directional);
    total += l.intensity.r;
    shadows += l.castsShadows ? 1 : 0;
  }
  EXPECT_NEAR(total, 2.0 * 4.0 * kPi, 1e-4);
  EXPECT_EQ(shadows, kEnvironmentShadowLights);
  EXPECT_THROW(medianCutEnvironment(map, 0, 0.0), std::invalid_argument);
  EXPECT_THROW(medianCutEnvironment(gpu::Image(), 4, 0.0), std::invalid_argument);
  env.file = "/nonexistent/env.hdr";
  EXPECT_THROW(environmentLights(env), std::runtime_error);
}

// The shipped studio map (data/MODELS.md): 72 % of its power is the spot lamp's glow around pixel
// (235, 133), so with 16 equal-power lights most of them point into that small patch, and their
// irradiance on an upward plane is close to the documented 13.9.
TEST(EnvironmentLights, ShippedStudioMap) {
  const gpu::Image map = gpu::readHdr(std::filesystem::path(TALLOW_TEST_DATA_DIR) / "env.hdr");
  const std::vector<EnvironmentLight> lights = medianCutEnvironment(map, 16, 0.0);
  ASSERT_EQ(lights.size(), 16u);
  const glm::dvec3 lamp = pixelDirection(map, 235.5, 133.5);
  int nearLamp = 0;
  double upward = 0.0;
  for (const EnvironmentLight& l : lights) {
    if (angleBetween(glm::dvec3(l.direction), lamp) < 0.15) ++nearLamp;
    upward += environmentLuminance(glm::vec4(l.irradiance, 1.0f)) * std::max(0.0f, l.direction.y);
  }
  EXPECT_GE(nearLamp, 8);
  EXPECT_NEAR(upward, 13.9, 13.9 * 0.15);
}

// The preset key "environment" (app/config/preset.cpp): values, defaults and file:line:col errors.
TEST(EnvironmentLights, PresetKey) {
  const std::filesystem::path data = TALLOW_TEST_DATA_DIR;
  const MaterialTable materials = MaterialTable::load(data / "materials.csv");
  auto parse = [&](const std::string& environment) {
    const std::string text = "{\"camera\": {\"position\": [0, 0, 1], \"target\": [0, 0, 0]},\n"
                             "\"objects\": [{\"shape\": \"sphere\"}],\n"
                             "\"environment\": " + environment + "}";
    return app::parsePreset(text, "p.json", "/presets", materials, data);
  };
  auto error = [&](const std::string& environment) -> std::string {
    try {
      parse(environment);
    } catch (const app::InputError& e) {
      return e.what();
    }
    return "";
  };
  const app::Config c = parse(R"({"file": "data:env.hdr", "lights": 8, "rotation_deg": -30, "intensity": 0.5})");
  ASSERT_TRUE(c.scene.environment.has_value());
  EXPECT_EQ(c.scene.environment->file, std::filesystem::absolute(data / "env.hdr").lexically_normal());
  EXPECT_EQ(c.scene.environment->lights, 8);
  EXPECT_EQ(c.scene.environment->rotationDeg, -30.0f);
  EXPECT_EQ(c.scene.environment->scale, 0.5f);
  EXPECT_TRUE(c.scene.lights.empty());  // the lights are made by loadScene, not by the reader
  const app::Config d = parse(R"({"file": "data:env.hdr"})");
  EXPECT_EQ(d.scene.environment->lights, 16);
  EXPECT_EQ(d.scene.environment->rotationDeg, 0.0f);
  EXPECT_EQ(d.scene.environment->scale, 1.0f);
  // Errors point at line 3 (the "environment" line), at the offending value or key.
  EXPECT_EQ(error(R"({"file": "data:env.hdr", "lights": 0})"), "p.json:3:51: lights: 0 is out of range [1, 32]");
  EXPECT_EQ(error(R"({"file": "data:env.hdr", "lights": 33})"), "p.json:3:51: lights: 33 is out of range [1, 32]");
  EXPECT_EQ(error(R"({"file": "data:env.hdr", "lights": 2.5})"), "p.json:3:51: lights: expected an integer");
  EXPECT_NE(error(R"({"file": "data:env.hdr", "ligths": 4})").find("p.json:3:41: unknown key \"ligths\" (did you mean \"lights\"?)"),
            std::string::npos);
  EXPECT_NE(error(R"({"file": "data:nope.hdr"})").find("p.json:3:25: file: no such file"), std::string::npos);
  EXPECT_EQ(error(R"({"file": 3})"), "p.json:3:25: file: expected a string (a Radiance .hdr file name)");
  EXPECT_EQ(error(R"({"lights": 4})"), "p.json:3:16: missing \"file\"");
  EXPECT_EQ(error(R"({"file": "data:env.hdr", "intensity": -1})"), "p.json:3:54: intensity: -1 is out of range [0, 1e+09]");
}

}  // namespace
}  // namespace tallow::sss
