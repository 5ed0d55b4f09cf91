// The registry parameters the view panel added (material.*, light.type, camera.height) and how the
// panel lays the registry out (app/view/view_param_widgets.h).
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "support/error_of.h"

#include "app/config/input_error.h"
#include "app/config/params.h"
#include "app/view/view_param_widgets.h"

namespace tallow::app {
namespace {

using json = nlohmann::json;

constexpr const char* kCsv =
    "name,source,sigma_s_r,sigma_s_g,sigma_s_b,sigma_a_r,sigma_a_g,sigma_a_b,g_r,g_g,g_b,eta,unit\n"
    "Marble,Jensen et al. 2001,2.19,2.62,3,0.0021,0.0041,0.0071,0,0,0,1.5,mm^-1\n";

class SceneEditParams : public ::testing::Test {
 protected:
  SceneEditParams() : table(sss::MaterialTable::parse(kCsv, "inline.csv")), registry(parameterRegistry(table)) {
    registry.applyDefaults(config);
    config.scene.objects.emplace_back();
    config.scene.camera.position = {0.0f, 0.0f, 2.0f};
    config.scene.camera.target = {0.0f, 0.0f, 0.0f};
  }
  std::string setError(const char* key, const json& value) {
    return test::errorOf<InputError>([&] { registry.set(config, key, value); });
  }

  sss::MaterialTable table;
  Registry registry;
  Config config;
};

TEST_F(SceneEditParams, MaterialCoefficientsOfTheFirstObject) {
  EXPECT_TRUE(registry.get(config, "material.eta").is_null()) << "an opaque object has no coefficients";
  EXPECT_EQ(setError("material.eta", 1.4), "material.eta: the first object is opaque (give it a material first)");
  registry.set(config, "material", "Marble");
  EXPECT_EQ(registry.get(config, "material.eta"), 1.5);
  registry.set(config, "material.eta", 1.5);  // the value it has: still the table's row
  EXPECT_EQ(config.scene.objects[0].material.name, "Marble");
  registry.set(config, "material.sigma_s", json::array({1.0, 2.0, 3.0}));
  EXPECT_EQ(config.scene.objects[0].material.sigma_s, glm::vec3(1.0f, 2.0f, 3.0f));
  // The measured material it came from stays named, with a mark; a second edit does not mark it twice.
  EXPECT_EQ(config.scene.objects[0].material.name, "Marble (modified)");
  registry.set(config, "material.eta", 1.4);
  EXPECT_EQ(config.scene.objects[0].material.name, "Marble (modified)");
  EXPECT_EQ(registry.get(config, "material"), "Marble (modified)");
  // sss::validateMaterial's checks refuse what a preset's would, and nothing changes.
  EXPECT_EQ(setError("material.g", json::array({0.0, 1.0, 0.0})), "material.g: g_g = 1 is not in (-1, 1)");
  EXPECT_EQ(setError("material.eta", 0.0), "material.eta: eta must be a positive number (0)");
  EXPECT_EQ(config.scene.objects[0].material.eta, 1.4f);
  EXPECT_EQ(setError("material.sigma_a", json::array({0.0, -1.0, 0.0})),
            "material.sigma_a: -1 is out of range [0, 1e+06] (component y)");
}

TEST_F(SceneEditParams, LightTypeKeepsTheIrradianceAtTheTarget) {
  sss::Light sun;
  sun.direction = glm::normalize(glm::vec3(0.0f, 3.0f, 4.0f));
  sun.intensity = {2.0f, 2.0f, 2.0f};  // W/m²
  config.scene.lights.push_back(sun);
  registry.set(config, "light.type", "point");
  const sss::Light& point = config.scene.lights[0];
  ASSERT_EQ(point.kind, sss::LightKind::Point);
  // At the camera's distance (2 m) along the direction: I = E d² = 2 · 4 W/sr.
  EXPECT_NEAR(glm::length(point.position - glm::vec3(0.0f, 1.2f, 1.6f)), 0.0f, 1e-6f);
  EXPECT_NEAR(point.intensity.x, 8.0f, 1e-5f);
  registry.set(config, "light.type", "directional");
  EXPECT_NEAR(glm::length(config.scene.lights[0].direction - sun.direction), 0.0f, 1e-6f);
  EXPECT_NEAR(config.scene.lights[0].intensity.x, 2.0f, 1e-5f);
  config.scene.lights[0].kind = sss::LightKind::Point;
  config.scene.lights[0].follow = 0;
  EXPECT_EQ(setError("light.type", "directional"),
            "light.type: the first light follows a candle's flame; pin it with light.position first");
}

TEST_F(SceneEditParams, OrthographicHeight) {
  EXPECT_TRUE(registry.get(config, "camera.height").is_null());
  EXPECT_EQ(setError("camera.height", 0.5),
            "camera.height: the camera is perspective (it has a field of view, not a height)");
  config.scene.camera.orthographic = true;
  registry.set(config, "camera.height", 0.5);
  EXPECT_EQ(config.scene.camera.orthoHeight, 0.5f);
}

TEST(ParamWidgets, GroupsAndWidgetsFollowTheDeclarations) {
  const std::vector<std::string> keys = {"sss.maps", "material", "material.eta", "method", "scale"};
  EXPECT_EQ(paramGroup("sss.maps", keys), "sss");
  EXPECT_EQ(paramGroup("material", keys), "material") << "joins the keys that extend it";
  EXPECT_EQ(paramGroup("method", keys), "general");
  const Registry registry = parameterRegistry(sss::MaterialTable::parse(kCsv, "inline.csv"));
  const auto widget = [&](const char* key) { return paramWidget(*registry.find(key)); };
  EXPECT_EQ(widget("render.shadows"), ParamWidget::Checkbox);
  EXPECT_EQ(widget("sss.model"), ParamWidget::Combo);
  EXPECT_EQ(widget("sss.maps"), ParamWidget::Slider);        // [1, 256]
  EXPECT_EQ(widget("render.width"), ParamWidget::LogSlider); // [1, 16384]
  EXPECT_EQ(widget("vpl.count"), ParamWidget::Drag);         // [0, 4096]: no logarithm through 0
  EXPECT_EQ(widget("sss.bias"), ParamWidget::Slider);        // [0, 1]
  EXPECT_EQ(widget("scale"), ParamWidget::LogSlider);        // [1e-5, 1e3] m
  EXPECT_EQ(widget("camera.position"), ParamWidget::Drag);   // ±1e4 m
  EXPECT_EQ(widget("light.direction"), ParamWidget::Slider); // [-1, 1] per component
  // Labels: the key without its group, with the unit unless it repeats the name.
  const auto label = [&](const char* key, const char* group) { return paramLabel(*registry.find(key), group); };
  EXPECT_EQ(label("sss.map_size", "sss"), "map_size [texels]");
  EXPECT_EQ(label("sss.maps", "sss"), "maps");
  EXPECT_EQ(label("material.sigma_a", "material"), "sigma_a [mm⁻¹]");
  EXPECT_EQ(label("sss.view_weight", "sss"), "view_weight");
  EXPECT_EQ(label("scale", "general"), "scale [m]");
  // Clearing "auto" keeps what the renderer chose, within the range; Param::autoOffValue (the
  // paper's 16 maps) only when nothing was chosen yet.
  const Registry::Param& maps = *registry.find("sss.maps");
  EXPECT_EQ(autoOffValue(maps, 12), 12);
  EXPECT_EQ(autoOffValue(maps, std::nullopt), 16);
  EXPECT_EQ(autoOffValue(maps, 100000), static_cast<std::int64_t>(maps.max));
  // Every unit is short enough for a label beside a widget (the help carries the explanation).
  for (const Registry::Param& p : registry.params()) EXPECT_LE(p.units.size(), 18u) << p.key << ": " << p.units;
}

}  // namespace
}  // namespace tallow::app
