// "Save as preset" (app/config/preset_writer.h): a preset written from a changed configuration reads back
// (app/config/preset.h) to the same registry values; paths are made absolute; what cannot round-trip is
// left out.
#include "app/config/preset_writer.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "app/config/params.h"
#include "app/config/preset.h"

namespace tallow::app {
namespace {

constexpr const char* kCsv =
    "name,source,sigma_s_r,sigma_s_g,sigma_s_b,sigma_a_r,sigma_a_g,sigma_a_b,g_r,g_g,g_b,eta,unit\n"
    "Marble,Jensen et al. 2001,2.19,2.62,3,0.0021,0.0041,0.0071,0,0,0,1.5,mm^-1\n"
    "Ketchup,Jensen et al. 2001,0.18,0.07,0.03,0.061,0.97,1.45,0,0,0,1.3,mm^-1\n";

constexpr const char* kPreset = R"({
  "name": "two",
  "camera": {"position": [0, 0.1, 0.3], "target": [0, 0.05, 0]},
  "lights": [{"type": "directional", "direction": [0, 1, 0], "irradiance": [1, 1, 1]}],
  "objects": [
    {"mesh": "meshes/thing.ply", "material": "Marble", "scale": 0.1},
    {"field": {"type": "blob"}, "material": {"from": "Ketchup", "scale": 2}},
    {"mesh": "data:bunny.ply"}
  ],
  "animation": {"duration_s": 13, "loop": true},
  "settings": {"sss.maps": 8}
})";

const sss::MaterialTable& table() {
  static const sss::MaterialTable t = sss::MaterialTable::parse(kCsv, "inline.csv");
  return t;
}

Config parse(const std::string& text) { return parsePreset(text, "p.json", "/presets", table(), "/data"); }

TEST(PresetWriter, ReadsBackToTheSameValues) {
  const Registry registry = parameterRegistry(table());
  Config config = parse(kPreset);
  // Changes of every kind the panel makes: a renderer setting, a material coefficient, the camera,
  // the light, the image size.
  registry.setFromString(config, "sss.maps=5");
  registry.setFromString(config, "material=Ketchup");  // another row than the preset's Marble, then edited
  registry.setFromString(config, "material.sigma_a=0.01,0.02,0.03");
  registry.setFromString(config, "material.eta=1.4");
  registry.setFromString(config, "camera.position=0.1,0.2,0.3");
  registry.setFromString(config, "light.direction=1,1,0");
  registry.setFromString(config, "render.tonemap=reinhard");
  registry.setFromString(config, "render.width=321");
  PresetState state;
  state.timeS = 4.25;
  state.loop = false;
  const std::string text = presetText(kPreset, config, registry, state);
  const Config back = parse(text);
  // The independent expectation is the configuration itself: every registry value, as the window had it.
  EXPECT_EQ(registry.snapshot(back), registry.snapshot(config)) << text;
  EXPECT_EQ(back.scene.startS, 4.25f);
  EXPECT_FALSE(back.scene.loop);
  EXPECT_EQ(back.scene.durationS, 13.0f);
  EXPECT_EQ(back.scene.objects[0].material.name, "Ketchup (modified)");
  EXPECT_EQ(back.scene.objects[1].material.name, "Ketchup x2");
  const nlohmann::json doc = nlohmann::json::parse(text);
  EXPECT_EQ(doc["objects"][0]["mesh"], "/presets/meshes/thing.ply") << "relative paths become absolute";
  EXPECT_EQ(doc["objects"][2]["mesh"], "data:bunny.ply") << "data: names stay";
  EXPECT_EQ(doc["settings"]["material"], "Ketchup") << "the edited row; material.* after it carry the edits";
  EXPECT_FALSE(doc["settings"].contains("camera.height")) << "null (a perspective camera) is left out";
  EXPECT_EQ(doc["settings"]["sss.maps"], 5);
}

TEST(PresetWriter, AFollowingLightKeepsFollowing) {
  const Registry registry = parameterRegistry(table());
  constexpr const char* kCandle = R"({
    "camera": {"position": [0, 0.1, 0.3], "target": [0, 0.05, 0]},
    "lights": [{"type": "point", "follow": "candle", "intensity": [1, 1, 1]}],
    "objects": [{"name": "candle", "field": {"type": "candle"}, "material": "Marble"}]
  })";
  const Config config = parse(kCandle);
  const std::string text = presetText(kCandle, config, registry, {});
  EXPECT_FALSE(nlohmann::json::parse(text)["settings"].contains("light.position")) << text;
  EXPECT_EQ(parse(text).scene.lights.front().follow, 0) << "the light still sits at the flame";
  EXPECT_EQ(parse(text).scene.objects.front().material.name, "Marble") << "a table row keeps its name";
}

}  // namespace
}  // namespace tallow::app
