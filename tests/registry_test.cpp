// The parameter registry: declarations, defaults, type and range checks, --set parsing, snapshot.
#include "app/config/registry.h"

#include <gtest/gtest.h>

#include "support/error_of.h"

#include <cmath>
#include <set>
#include <string>

#include "app/config/input_error.h"
#include "app/config/params.h"

namespace tallow::app {
namespace {

using json = nlohmann::json;

constexpr const char* kCsv =
    "name,source,sigma_s_r,sigma_s_g,sigma_s_b,sigma_a_r,sigma_a_g,sigma_a_b,g_r,g_g,g_b,eta,unit\n"
    "Marble,Jensen et al. 2001,2.19,2.62,3,0.0021,0.0041,0.0071,0,0,0,1.5,mm^-1\n"
    "Ketchup,Jensen et al. 2001,0.18,0.07,0.03,0.061,0.97,1.45,0,0,0,1.3,mm^-1\n";

template <typename F>
std::string errorOf(F&& f) {
  return test::errorOf<InputError>(std::forward<F>(f));
}

class RegistryTest : public ::testing::Test {
 protected:
  RegistryTest() : table(sss::MaterialTable::parse(kCsv, "inline.csv")), registry(parameterRegistry(table)) {
    registry.applyDefaults(config);
  }

  /// A scene with one object and one light of the given kind.
  void addSceneContent(sss::LightKind kind = sss::LightKind::Directional) {
    config.scene.objects.emplace_back();
    sss::Light light;
    light.kind = kind;
    config.scene.lights.push_back(light);
  }

  std::string setError(const char* key, const json& value) {
    return errorOf([&] { registry.set(config, key, value); });
  }
  std::string setStringError(const char* assignment) {
    return errorOf([&] { registry.setFromString(config, assignment); });
  }

  sss::MaterialTable table;
  Registry registry;
  Config config;
};

TEST_F(RegistryTest, DeclaresTheContractKeysOnceWithHelp) {
  const std::set<std::string> expected = {
      "render.width",    "render.height",   "render.shadows",  "render.shadow_map_size", "render.shadow_bias",
      "render.pcf_radius", "render.tonemap", "render.exposure_ev", "field.res", "scale", "material", "light.intensity",
      "light.direction", "light.position",  "camera.position", "camera.target", "camera.fov_deg", "ambient"};
  std::set<std::string> keys;
  for (const Registry::Param& p : registry.params()) {
    EXPECT_TRUE(keys.insert(p.key).second) << p.key;
    EXPECT_FALSE(p.help.empty()) << p.key;
    EXPECT_TRUE(p.getter && p.setter) << p.key;
    if (p.type == "int" || p.type == "float" || p.type == "vec3") {
      EXPECT_LT(p.min, p.max) << p.key;
    }
  }
  for (const std::string& k : expected) EXPECT_TRUE(keys.count(k)) << k;
  EXPECT_EQ(registry.find("nope"), nullptr);
  ASSERT_NE(registry.find("render.width"), nullptr);
  EXPECT_EQ(registry.find("render.width")->units, "px");
  EXPECT_EQ(registry.find("scale")->units, "m");
  EXPECT_EQ(registry.find("render.exposure_ev")->units, "stops");
}

TEST_F(RegistryTest, DefaultsAndSceneBoundParameters) {
  EXPECT_EQ(config.render.width, 960);
  EXPECT_EQ(config.render.height, 540);
  EXPECT_TRUE(config.render.shadows);
  EXPECT_EQ(config.render.shadowMapSize, 2048);
  EXPECT_FLOAT_EQ(config.render.shadowBias, 1.5f);
  EXPECT_EQ(config.render.pcfRadius, 1);
  EXPECT_EQ(config.render.toneMap.op, gpu::ToneMap::Aces);
  EXPECT_FLOAT_EQ(config.render.toneMap.exposureEv, 0.0f);
  for (const char* key : {"scale", "material", "light.intensity", "light.direction", "light.position",
                          "camera.position", "camera.target", "camera.fov_deg", "ambient"}) {
    EXPECT_TRUE(registry.find(key)->sceneBound()) << key;
    EXPECT_FALSE(registry.find(key)->defaultValue) << key;
  }
  EXPECT_FALSE(registry.find("render.width")->sceneBound());
}

TEST_F(RegistryTest, MaterialChoicesComeFromTheTable) {
  EXPECT_EQ(registry.find("material")->choices, (std::vector<std::string>{"Marble", "Ketchup"}));
}

TEST_F(RegistryTest, IntChecksTypeAndRange) {
  registry.set(config, "render.pcf_radius", 4);
  EXPECT_EQ(config.render.pcfRadius, 4);
  registry.set(config, "render.pcf_radius", 0);
  EXPECT_EQ(config.render.pcfRadius, 0);
  EXPECT_EQ(setError("render.pcf_radius", 5), "render.pcf_radius: 5 is out of range [0, 4]");
  EXPECT_EQ(setError("render.pcf_radius", -1), "render.pcf_radius: -1 is out of range [0, 4]");
  EXPECT_EQ(setError("render.width", 0), "render.width: 0 is out of range [1, 16384]");
  EXPECT_EQ(setError("render.width", 16385), "render.width: 16385 is out of range [1, 16384]");
  EXPECT_EQ(setError("render.width", json(18446744073709551615ull)),
            "render.width: 18446744073709551616 is out of range [1, 16384]");
  EXPECT_EQ(setError("render.width", 2.5), "render.width: expected an integer, got 2.5");
  EXPECT_EQ(setError("render.width", "wide"), "render.width: expected an integer, got \"wide\"");
  EXPECT_EQ(config.render.width, 960);  // unchanged by the failures
  registry.set(config, "render.shadow_map_size", 16);
  EXPECT_EQ(config.render.shadowMapSize, 16);
  EXPECT_EQ(setError("render.shadow_map_size", 15), "render.shadow_map_size: 15 is out of range [16, 16384]");
}

TEST_F(RegistryTest, FloatChecksTypeAndRange) {
  registry.set(config, "render.shadow_bias", 16);  // an integer is a number too
  EXPECT_FLOAT_EQ(config.render.shadowBias, 16.0f);
  registry.set(config, "render.exposure_ev", -2.5);
  EXPECT_FLOAT_EQ(config.render.toneMap.exposureEv, -2.5f);
  EXPECT_EQ(setError("render.shadow_bias", -0.5), "render.shadow_bias: -0.5 is out of range [0, 16]");
  EXPECT_EQ(setError("render.exposure_ev", 20.5), "render.exposure_ev: 20.5 is out of range [-20, 20]");
  EXPECT_EQ(setError("render.exposure_ev", true), "render.exposure_ev: expected a number, got true");
  EXPECT_EQ(setError("render.exposure_ev", nullptr), "render.exposure_ev: expected a number, got null");
}

TEST_F(RegistryTest, BoolAndEnum) {
  registry.set(config, "render.shadows", false);
  EXPECT_FALSE(config.render.shadows);
  EXPECT_EQ(setError("render.shadows", 1), "render.shadows: expected true or false, got 1");
  registry.set(config, "render.tonemap", "reinhard");
  EXPECT_EQ(config.render.toneMap.op, gpu::ToneMap::Reinhard);
  EXPECT_EQ(setError("render.tonemap", "acse"),
            "render.tonemap: unknown value \"acse\" (did you mean \"aces\"?); choices: clamp, reinhard, aces, hue-preserving");
  EXPECT_EQ(setError("render.tonemap", "filmic"),
            "render.tonemap: unknown value \"filmic\"; choices: clamp, reinhard, aces, hue-preserving");
  EXPECT_EQ(setError("render.tonemap", 2), "render.tonemap: expected a string, got 2");
  registry.set(config, "render.tonemap", "hue-preserving");
  EXPECT_EQ(config.render.toneMap.op, gpu::ToneMap::HuePreserving);
}

TEST_F(RegistryTest, FieldPlacementIsAnEnumDefaultingToTheExtractorsDefault) {
  EXPECT_EQ(config.render.fieldPlacement, geometry::kDefaultPlacement);
  EXPECT_EQ(registry.find("field.placement")->choices, (std::vector<std::string>{"qef", "mass"}));
  registry.set(config, "field.placement", "mass");
  EXPECT_EQ(config.render.fieldPlacement, geometry::VertexPlacement::Mass);
  registry.set(config, "field.placement", "qef");
  EXPECT_EQ(config.render.fieldPlacement, geometry::VertexPlacement::Qef);
  EXPECT_EQ(setError("field.placement", "qfe"),
            "field.placement: unknown value \"qfe\" (did you mean \"qef\"?); choices: qef, mass");
}

TEST_F(RegistryTest, FieldEvaluateIsGpuByDefaultAndCpuOnRequest) {
  EXPECT_TRUE(config.render.fieldOnGpu);
  EXPECT_EQ(registry.get(config, "field.evaluate"), "gpu");
  EXPECT_EQ(registry.find("field.evaluate")->choices, (std::vector<std::string>{"gpu", "cpu"}));
  registry.set(config, "field.evaluate", "cpu");
  EXPECT_FALSE(config.render.fieldOnGpu);
  EXPECT_EQ(registry.get(config, "field.evaluate"), "cpu");
  EXPECT_EQ(setError("field.evaluate", "gpus"),
            "field.evaluate: unknown value \"gpus\" (did you mean \"gpu\"?); choices: gpu, cpu");
}

TEST_F(RegistryTest, FieldExtractionIsComputeByDefaultAndGeometryShadersOnRequest) {
  EXPECT_EQ(config.render.fieldExtraction, geometry::ExtractionPath::Compute);
  EXPECT_EQ(registry.get(config, "field.extraction"), "compute");
  EXPECT_EQ(registry.find("field.extraction")->choices, (std::vector<std::string>{"compute", "geometry"}));
  registry.set(config, "field.extraction", "geometry");
  EXPECT_EQ(config.render.fieldExtraction, geometry::ExtractionPath::GeometryShader);
  EXPECT_EQ(registry.get(config, "field.extraction"), "geometry");
  EXPECT_EQ(setError("field.extraction", "geometri"),
            "field.extraction: unknown value \"geometri\" (did you mean \"geometry\"?); choices: compute, geometry");
}

TEST_F(RegistryTest, MapSizesAndCountAreAutoByDefaultAndTakeAnIntegerOrAuto) {
  for (const char* key : {"sss.map_size", "sss.light_map_size", "sss.maps"}) {
    SCOPED_TRACE(key);
    EXPECT_EQ(registry.get(config, key), "auto");
    registry.setFromString(config, std::string(key) + "=256");
    EXPECT_EQ(registry.get(config, key), 256);
    registry.setFromString(config, std::string(key) + "= auto");
    EXPECT_EQ(registry.get(config, key), "auto");
    registry.set(config, key, 64);
    EXPECT_EQ(registry.get(config, key), 64);
    registry.set(config, key, "auto");
    EXPECT_EQ(registry.get(config, key), "auto");
  }
  EXPECT_EQ(config.render.sss.mapSize, sss::kAuto);
  EXPECT_EQ(config.render.sss.maps, sss::kAuto);
  EXPECT_EQ(setError("sss.map_size", "automatic"), "sss.map_size: expected an integer or \"auto\", got \"automatic\"");
  EXPECT_EQ(setError("sss.map_size", 8), "sss.map_size: 8 is out of range [16, 8192]");
  EXPECT_EQ(setError("sss.samples", "auto"), "sss.samples: expected an integer, got \"auto\"");
  EXPECT_EQ(setError("sss.maps", 300), "sss.maps: 300 is out of range [1, 256]");
  EXPECT_EQ(setStringError("sss.light_map_size=big"), "sss.light_map_size: \"big\" is neither an integer nor auto");
}

TEST_F(RegistryTest, Vec3ChecksShapeAndEachComponent) {
  EXPECT_EQ(setError("ambient", json::array({1, 2})), "ambient: expected an array of 3 numbers, got [1,2]");
  EXPECT_EQ(setError("ambient", json::array({1, "2", 3})), "ambient: expected an array of 3 numbers, got [1,\"2\",3]");
  EXPECT_EQ(setError("ambient", 1.0), "ambient: expected an array of 3 numbers, got 1.0");
  EXPECT_EQ(setError("ambient", json::array({0.1, -1, 0})), "ambient: -1 is out of range [0, 1e+09] (component y)");
  registry.set(config, "ambient", json::array({0.1, 0.2, 0.3}));
  EXPECT_EQ(config.scene.ambient, glm::vec3(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(registry.get(config, "ambient"), json::parse("[0.1, 0.2, 0.3]"));  // no float noise
}

TEST_F(RegistryTest, UnknownKeysSuggestTheClosest) {
  EXPECT_EQ(setError("render.widht", 3), "unknown parameter \"render.widht\" (did you mean \"render.width\"?)");
  EXPECT_EQ(setError("materail", "Marble"), "unknown parameter \"materail\" (did you mean \"material\"?)");
  EXPECT_EQ(setError("foo", 3), "unknown parameter \"foo\"");
  EXPECT_EQ(errorOf([&] { registry.get(config, "Scale"); }), "unknown parameter \"Scale\" (did you mean \"scale\"?)");
  EXPECT_EQ(setStringError("render.tonemapp=aces"),
            "unknown parameter \"render.tonemapp\" (did you mean \"render.tonemap\"?)");
}

TEST_F(RegistryTest, SceneBoundParametersNeedTheirSceneContent) {
  EXPECT_EQ(setError("scale", 0.5), "scale: the scene has no objects");
  EXPECT_EQ(setError("material", "Marble"), "material: the scene has no objects");
  EXPECT_EQ(setError("light.intensity", json::array({1, 1, 1})), "light.intensity: the scene has no lights");
  EXPECT_EQ(setError("light.direction", json::array({0, 1, 0})), "light.direction: the scene has no lights");
  EXPECT_EQ(registry.get(config, "scale"), nullptr);
  EXPECT_EQ(registry.get(config, "material"), nullptr);
  EXPECT_EQ(registry.get(config, "light.intensity"), nullptr);

  addSceneContent(sss::LightKind::Directional);
  registry.set(config, "scale", 0.1);
  EXPECT_FLOAT_EQ(config.scene.objects[0].transform.scale, 0.1f);
  EXPECT_EQ(setError("scale", 0), "scale: 0 is out of range [1e-05, 1000]");
  EXPECT_EQ(registry.get(config, "material"), nullptr);  // not translucent yet
  registry.set(config, "material", "Ketchup");
  EXPECT_TRUE(config.scene.objects[0].translucent);
  EXPECT_EQ(config.scene.objects[0].material.name, "Ketchup");
  EXPECT_FLOAT_EQ(config.scene.objects[0].material.sigma_a.b, 1.45f);
  EXPECT_EQ(registry.get(config, "material"), "Ketchup");
  EXPECT_EQ(setError("material", "Marbel"), "material: unknown value \"Marbel\" (did you mean \"Marble\"?); choices: Marble, Ketchup");

  registry.set(config, "light.direction", json::array({0, 0.6, 0.8}));
  EXPECT_NEAR(glm::length(config.scene.lights[0].direction), 1.0f, 1e-6f);
  registry.set(config, "light.direction", json::array({1, 1, 0}));  // normalised on set
  EXPECT_NEAR(config.scene.lights[0].direction.x, std::sqrt(0.5f), 1e-6f);
  EXPECT_NEAR(config.scene.lights[0].direction.y, std::sqrt(0.5f), 1e-6f);
  EXPECT_EQ(setError("light.direction", json::array({0, 0, 0})), "light.direction: the direction must not be zero");
  registry.set(config, "light.direction", json::array({1e-40, 0, 0}));  // tiny but not zero
  EXPECT_EQ(config.scene.lights[0].direction, glm::vec3(1, 0, 0));
  EXPECT_EQ(setError("light.direction", json::array({0, 2, 0})),
            "light.direction: 2 is out of range [-1, 1] (component y)");
  EXPECT_EQ(setError("light.position", json::array({0, 1, 0})),
            "light.position: the first light is directional (it has light.direction)");
  EXPECT_EQ(registry.get(config, "light.position"), nullptr);
  registry.set(config, "light.intensity", json::array({1, 2, 3}));
  EXPECT_EQ(config.scene.lights[0].intensity, glm::vec3(1, 2, 3));

  config.scene.lights[0].kind = sss::LightKind::Point;
  registry.set(config, "light.position", json::array({0.5, 1, -2}));
  EXPECT_EQ(config.scene.lights[0].position, glm::vec3(0.5f, 1, -2));
  EXPECT_EQ(setError("light.direction", json::array({0, 1, 0})),
            "light.direction: the first light is a point light (it has light.position)");
  EXPECT_EQ(registry.get(config, "light.direction"), nullptr);
}

TEST_F(RegistryTest, Camera) {
  registry.set(config, "camera.position", json::array({1, 2, 3}));
  registry.set(config, "camera.target", json::array({0, 0.5, 0}));
  registry.set(config, "camera.fov_deg", 50);
  EXPECT_EQ(config.scene.camera.position, glm::vec3(1, 2, 3));
  EXPECT_EQ(config.scene.camera.target, glm::vec3(0, 0.5f, 0));
  EXPECT_FLOAT_EQ(config.scene.camera.fovYDeg, 50.0f);
  EXPECT_EQ(setError("camera.fov_deg", 180), "camera.fov_deg: 180 is out of range [1, 179]");
  EXPECT_EQ(setError("camera.position", json::array({0, 0, 1e5})),
            "camera.position: 1e+05 is out of range [-10000, 10000] (component z)");
  config.scene.camera.orthographic = true;
  EXPECT_EQ(setError("camera.fov_deg", 50),
            "camera.fov_deg: the camera is orthographic (it has a height, not a field of view)");
  EXPECT_EQ(registry.get(config, "camera.fov_deg"), nullptr);
}

TEST_F(RegistryTest, SetFromStringParsesByType) {
  for (const auto& [text, expected] : {std::pair{"true", true}, {"1", true}, {"on", true}, {"false", false},
                                       {"0", false}, {"off", false}}) {
    registry.setFromString(config, std::string("render.shadows=") + text);
    EXPECT_EQ(config.render.shadows, expected) << text;
  }
  EXPECT_EQ(setStringError("render.shadows=yes"),
            "render.shadows: expected true/false, 1/0 or on/off, got \"yes\"");
  registry.setFromString(config, "render.width=1280");
  EXPECT_EQ(config.render.width, 1280);
  registry.setFromString(config, " render.height = 720 ");  // spaces around key and value
  EXPECT_EQ(config.render.height, 720);
  EXPECT_EQ(setStringError("render.width=12.5"), "render.width: \"12.5\" is not an integer");
  EXPECT_EQ(setStringError("render.width=0x10"), "render.width: \"0x10\" is not an integer");
  EXPECT_EQ(setStringError("render.width="), "render.width: \"\" is not an integer");
  EXPECT_EQ(setStringError("render.width=99999"), "render.width: 99999 is out of range [1, 16384]");
  registry.setFromString(config, "render.exposure_ev=-1.5");
  EXPECT_FLOAT_EQ(config.render.toneMap.exposureEv, -1.5f);
  registry.setFromString(config, "render.exposure_ev=2");
  EXPECT_FLOAT_EQ(config.render.toneMap.exposureEv, 2.0f);
  EXPECT_EQ(setStringError("render.exposure_ev=bright"), "render.exposure_ev: \"bright\" is not a number");
  EXPECT_EQ(setStringError("render.exposure_ev=nan"), "render.exposure_ev: nan is not a finite number");
  EXPECT_EQ(setStringError("render.exposure_ev=inf"), "render.exposure_ev: inf is not a finite number");
  registry.setFromString(config, "render.tonemap=clamp");
  EXPECT_EQ(config.render.toneMap.op, gpu::ToneMap::Clamp);
  registry.setFromString(config, "ambient=0.1,0.2,0.3");
  EXPECT_EQ(config.scene.ambient, glm::vec3(0.1f, 0.2f, 0.3f));
  registry.setFromString(config, "ambient= 1 , 2 ,3");
  EXPECT_EQ(config.scene.ambient, glm::vec3(1, 2, 3));
  EXPECT_EQ(setStringError("ambient=1,2"), "ambient: expected three numbers x,y,z, got \"1,2\"");
  EXPECT_EQ(setStringError("ambient=1,2,3,4"), "ambient: expected three numbers x,y,z, got \"1,2,3,4\"");
  EXPECT_EQ(setStringError("ambient=1,,3"), "ambient: expected three numbers x,y,z, got \"1,,3\"");
  EXPECT_EQ(setStringError("ambient=1,-2,3"), "ambient: -2 is out of range [0, 1e+09] (component y)");
  EXPECT_EQ(setStringError("render.width"), "expected key=value, got \"render.width\"");
  addSceneContent();
  registry.setFromString(config, "material=Marble");
  EXPECT_EQ(config.scene.objects[0].material.name, "Marble");
  registry.setFromString(config, "light.direction=0,1,0");
  EXPECT_EQ(config.scene.lights[0].direction, glm::vec3(0, 1, 0));
}

TEST_F(RegistryTest, SnapshotHasEveryKey) {
  json s = registry.snapshot(config);
  ASSERT_TRUE(s.is_object());
  EXPECT_EQ(s.size(), registry.params().size());
  for (const Registry::Param& p : registry.params()) EXPECT_TRUE(s.contains(p.key)) << p.key;
  EXPECT_EQ(s["render.width"], 960);
  EXPECT_EQ(s["render.shadow_bias"], 1.5);
  EXPECT_EQ(s["render.tonemap"], "aces");
  EXPECT_EQ(s["render.shadows"], true);
  EXPECT_EQ(s["scale"], nullptr);  // no objects in this scene
  EXPECT_EQ(s["light.direction"], nullptr);
  addSceneContent();
  registry.set(config, "scale", 0.1);
  s = registry.snapshot(config);
  EXPECT_EQ(s["scale"], 0.1);
  EXPECT_EQ(s["light.direction"], json::parse("[0, 1, 0]"));
  // Every value in a snapshot can be set back.
  Config copy = config;
  for (const auto& [key, value] : s.items())
    if (!value.is_null()) {
      EXPECT_NO_THROW(registry.set(copy, key, value)) << key;
    }
}

TEST(Registry, MaterialFromTheSharedTable) {
  const sss::MaterialTable materials = sss::MaterialTable::load(TALLOW_TEST_DATA_DIR "/materials.csv");
  const Registry registry = parameterRegistry(materials);
  EXPECT_EQ(registry.find("material")->choices.size(), 52u);
  Config config;
  config.scene.objects.emplace_back();
  registry.setFromString(config, "material=Head & Shoulders Shampoo");
  EXPECT_EQ(config.scene.objects[0].material.name, "Head & Shoulders Shampoo");
  // 52 choices are too many to list in one line: only the suggestion.
  EXPECT_EQ(errorOf([&] { registry.set(config, "material", "Marbel"); }),
            "material: unknown value \"Marbel\" (did you mean \"Marble\"?)");
}

TEST(Registry, DeclarationErrorsAreLogicErrors) {
  Registry r;
  Registry::Param p;
  p.key = "x";
  p.type = "int";
  p.min = 0;
  p.max = 4;
  p.defaultValue = 5;
  p.getter = [](const Config&) { return json(); };
  p.setter = [](Config&, const json&) {};
  EXPECT_THROW(r.add(p), std::logic_error);  // default out of range
  p.defaultValue = 3;
  r.add(p);
  EXPECT_THROW(r.add(p), std::logic_error);  // declared twice
  p.key = "y";
  p.type = "double";
  EXPECT_THROW(r.add(p), std::logic_error);  // unknown type
  p.type = "float";
  p.max = 1e300;
  EXPECT_THROW(r.add(p), std::logic_error);  // beyond float
}

TEST(Registry, Formatting) {
  EXPECT_EQ(formatNumber(1e-5), "1e-05");
  EXPECT_EQ(formatNumber(2048), "2048");
  EXPECT_EQ(formatNumber(0.1), "0.1");
  EXPECT_EQ(floatToJson(0.1f).dump(), "0.1");
  EXPECT_EQ(floatToJson(1.5f).dump(), "1.5");
}

TEST(InputErrorHints, EditDistanceAndSuggestions) {
  EXPECT_EQ(editDistance("mpas", "maps"), 1u);  // a transposition is one edit
  EXPECT_EQ(editDistance("kitten", "sitting"), 3u);
  EXPECT_EQ(editDistance("", "abc"), 3u);
  EXPECT_EQ(editDistance("Marble", "marble"), 0u);
  EXPECT_EQ(didYouMean("Marbel", {"Apple", "Marble"}), " (did you mean \"Marble\"?)");
  EXPECT_EQ(didYouMean("marble", {"Apple", "Marble"}), " (did you mean \"Marble\"?)");
  EXPECT_EQ(didYouMean("xyz", {"Apple", "Marble"}), "");
  EXPECT_EQ(didYouMean("", {"a"}), "");
  EXPECT_EQ(didYouMean("fov", {"fov_deg", "height"}), " (did you mean \"fov_deg\"?)");  // abbreviation
}

TEST(InputErrorHints, QuoteKeepsMessagesOnOneLine) {
  EXPECT_EQ(quote("plain"), "\"plain\"");
  EXPECT_EQ(quote("a\"b\\c\nd\te"), "\"a\\\"b\\\\c\\u000ad\\u0009e\"");
  EXPECT_EQ(quote(std::string(100, 'x')), "\"" + std::string(60, 'x') + "...\"");
  // Cut before a multi-byte character rather than through it.
  EXPECT_EQ(quote(std::string(59, 'x') + "\xCF\x83" + "tail"), "\"" + std::string(59, 'x') + "...\"");
}

}  // namespace
}  // namespace tallow::app
