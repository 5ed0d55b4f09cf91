// Presets: the shipped bunny, every field, and an exact file:line:col for each class of error.
#include "app/config/preset.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "app/config/input_error.h"
#include "app/config/params.h"

namespace tallow::app {
namespace {

namespace fs = std::filesystem;

const fs::path kDataDir = TALLOW_TEST_DATA_DIR;
const fs::path kPresetDir = fs::path(TALLOW_TEST_SOURCE_DIR) / "presets";

constexpr const char* kCsv =
    "name,source,sigma_s_r,sigma_s_g,sigma_s_b,sigma_a_r,sigma_a_g,sigma_a_b,g_r,g_g,g_b,eta,unit\n"
    "Marble,Jensen et al. 2001,2.19,2.62,3,0.0021,0.0041,0.0071,0,0,0,1.5,mm^-1\n"
    "Ketchup,Jensen et al. 2001,0.18,0.07,0.03,0.061,0.97,1.45,0,0,0,1.3,mm^-1\n";

const sss::MaterialTable& table() {
  static const sss::MaterialTable t = sss::MaterialTable::parse(kCsv, "inline.csv");
  return t;
}

Config parse(const std::string& text) { return parsePreset(text, "p.json", "/presets", table(), "/data"); }

std::string errorOf(const std::string& text) {
  try {
    parse(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

/// A preset whose fourth line, from column 5, is `object`:
///   line 1 {
///   line 2   "camera": {...},
///   line 3   "objects": [
///   line 4       <object>
///   line 5   ]
///   line 6 }
std::string withObject(const std::string& object, const std::string& extraTopLevel = "") {
  return "{\n"
         "  \"camera\": {\"position\": [0, 0.1, 0.3], \"target\": [0, 0.05, 0]},\n"
         "  \"objects\": [\n"
         "    " + object + "\n"
         "  ]" + extraTopLevel + "\n"
         "}\n";
}

/// A preset with one sphere whose third line, from column 3, is `line`:
///   line 1 {
///   line 2   "objects": [{"shape": "sphere"}], "camera": {...},   (no camera if !withCamera)
///   line 3   <line>
///   line 4 }
std::string withTopLevel(const std::string& line, bool withCamera = true) {
  return "{\n"
         "  \"objects\": [{\"shape\": \"sphere\"}]," +
         std::string(withCamera ? " \"camera\": {\"position\": [0, 0, 1], \"target\": [0, 0, 0]}," : "") + "\n"
         "  " + line + "\n"
         "}\n";
}

/// withTopLevel for lines that give the camera themselves.
std::string withCamera(const std::string& cameraLine) { return withTopLevel(cameraLine, false); }

TEST(Preset, BunnyLoads) {
  const sss::MaterialTable materials = sss::MaterialTable::load(kDataDir / "materials.csv");
  const fs::path file = resolvePresetName("bunny", kPresetDir);
  EXPECT_EQ(file, kPresetDir / "bunny.json");
  const Config c = loadPreset(file, materials, kDataDir);
  const sss::Scene& s = c.scene;
  EXPECT_EQ(s.name, "bunny");
  EXPECT_FALSE(s.description.empty());
  EXPECT_EQ(s.sourcePath, fs::absolute(file).lexically_normal());
  ASSERT_EQ(s.objects.size(), 2u);
  const sss::SceneObject& bunny = s.objects[0];
  EXPECT_EQ(bunny.shape, sss::ShapeKind::Mesh);
  EXPECT_EQ(bunny.meshPath, fs::absolute(kDataDir / "bunny.ply").lexically_normal());
  EXPECT_TRUE(fs::exists(bunny.meshPath));
  EXPECT_TRUE(bunny.translucent);
  EXPECT_EQ(bunny.material.name, "Marble");
  EXPECT_FLOAT_EQ(bunny.material.eta, 1.5f);
  EXPECT_FLOAT_EQ(bunny.transform.scale, 0.1f);
  EXPECT_EQ(bunny.albedo, glm::vec3(0.8f));
  const sss::SceneObject& ground = s.objects[1];
  EXPECT_EQ(ground.shape, sss::ShapeKind::Plane);
  EXPECT_FALSE(ground.translucent);
  EXPECT_FLOAT_EQ(ground.size.x, 2.0f);
  EXPECT_FLOAT_EQ(ground.size.z, 2.0f);
  EXPECT_EQ(ground.albedo, glm::vec3(0.5f));
  EXPECT_EQ(ground.transform.position.y, 0.0f);
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].kind, sss::LightKind::Directional);
  EXPECT_NEAR(glm::length(s.lights[0].direction), 1.0f, 1e-6f);
  EXPECT_LT(s.lights[0].direction.x, 0.0f);  // from the left,
  EXPECT_GT(s.lights[0].direction.y, 0.0f);  // above
  EXPECT_GT(s.lights[0].direction.z, 0.0f);  // and the front (the camera's side)
  EXPECT_TRUE(s.lights[0].castsShadows);
  EXPECT_EQ(s.lights[0].intensity, glm::vec3(2.4f));
  EXPECT_FALSE(s.camera.orthographic);
  EXPECT_GT(s.camera.position.z, 0.0f);
  // The bunny (0.1 m tall) fills about half the frame height at the target distance.
  const float distance = glm::length(s.camera.target - s.camera.position);
  const float visibleHeight = 2.0f * distance * std::tan(glm::radians(s.camera.fovYDeg) / 2.0f);
  EXPECT_NEAR(0.1f / visibleHeight, 0.5f, 0.1f);
  EXPECT_EQ(c.render.width, 960);  // registry defaults applied
}

TEST(Preset, ResolvesNamesAndPaths) {
  EXPECT_EQ(resolvePresetName((kPresetDir / "bunny.json").string(), "/elsewhere"), kPresetDir / "bunny.json");
  try {
    resolvePresetName("bunyn", kPresetDir);
    FAIL();
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.rfind("unknown preset \"bunyn\" (did you mean \"bunny\"?); available: ", 0), 0u) << m;
    EXPECT_NE(m.find("bunny"), std::string::npos) << m;
  }
  EXPECT_THROW(resolvePresetName("", kPresetDir), InputError);
  try {
    resolvePresetName("no/such.json", kPresetDir);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "no preset file \"no/such.json\"");
  }
}

TEST(Preset, ReadsEveryField) {
  const Config c = parse(R"({
    "name": "test", "description": "all fields",
    "camera": {"type": "orthographic", "position": [0, 1, 2], "target": [0, 0, 0], "up": [0, 0, -2], "height": 0.5},
    "lights": [
      {"type": "directional", "direction": [0, 0, 3], "irradiance": [1, 2, 3], "shadows": false},
      {"type": "point", "position": [1, 2, 3], "intensity": [4, 5, 6]}
    ],
    "objects": [
      {"name": "m", "mesh": "meshes/a.ply", "material": {"sigma_s": [1, 2, 3], "sigma_a": [0.1, 0.2, 0.3], "g": 0.5},
       "albedo": [0.1, 0.2, 0.3], "position": [1, 2, 3], "rotation_deg": [90, 0, -45], "scale": 2},
      {"shape": "box", "size": [1, 2, 3]},
      {"shape": "sphere", "material": {"sigma_s": [1, 1, 1], "sigma_a": [0, 0, 0], "g": [0.1, 0.2, 0.3], "eta": 1.4}},
      {"mesh": "/abs/b.ply"}
    ],
    "ambient": [0.1, 0.1, 0.1], "background": [0.2, 0.3, 0.4],
    "animation": {"duration_s": 4.5, "loop": false},
    "settings": {"render.width": 320, "render.tonemap": "clamp", "material": "Ketchup", "scale": 3}
  })");
  const sss::Scene& s = c.scene;
  EXPECT_EQ(s.name, "test");
  EXPECT_EQ(s.description, "all fields");
  EXPECT_EQ(s.sourcePath, fs::path("p.json"));
  EXPECT_TRUE(s.camera.orthographic);
  EXPECT_EQ(s.camera.up, glm::vec3(0, 0, -1));
  EXPECT_FLOAT_EQ(s.camera.orthoHeight, 0.5f);
  ASSERT_EQ(s.lights.size(), 2u);
  EXPECT_EQ(s.lights[0].direction, glm::vec3(0, 0, 1));
  EXPECT_EQ(s.lights[0].intensity, glm::vec3(1, 2, 3));
  EXPECT_FALSE(s.lights[0].castsShadows);
  EXPECT_EQ(s.lights[1].kind, sss::LightKind::Point);
  EXPECT_EQ(s.lights[1].position, glm::vec3(1, 2, 3));
  EXPECT_EQ(s.lights[1].intensity, glm::vec3(4, 5, 6));
  EXPECT_TRUE(s.lights[1].castsShadows);
  ASSERT_EQ(s.objects.size(), 4u);
  EXPECT_EQ(s.objects[0].name, "m");
  EXPECT_EQ(s.objects[0].meshPath, fs::path("/presets/meshes/a.ply"));
  EXPECT_EQ(s.objects[0].albedo, glm::vec3(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(s.objects[0].transform.position, glm::vec3(1, 2, 3));
  EXPECT_EQ(s.objects[0].transform.rotationDeg, glm::vec3(90, 0, -45));
  // "settings" come after the scene: material and scale of the first object are overridden.
  EXPECT_EQ(s.objects[0].material.name, "Ketchup");
  EXPECT_FLOAT_EQ(s.objects[0].transform.scale, 3.0f);
  EXPECT_EQ(c.render.width, 320);
  EXPECT_EQ(c.render.toneMap.op, gpu::ToneMap::Clamp);
  EXPECT_EQ(c.render.height, 540);  // default
  EXPECT_EQ(s.objects[1].shape, sss::ShapeKind::Box);
  EXPECT_EQ(s.objects[1].size, glm::vec3(1, 2, 3));
  EXPECT_FALSE(s.objects[1].translucent);
  EXPECT_EQ(s.objects[1].name, "box");
  EXPECT_EQ(s.objects[2].shape, sss::ShapeKind::Sphere);
  EXPECT_TRUE(s.objects[2].translucent);
  EXPECT_EQ(s.objects[2].material.name, "custom");
  EXPECT_EQ(s.objects[2].material.g, glm::vec3(0.1f, 0.2f, 0.3f));
  EXPECT_FLOAT_EQ(s.objects[2].material.eta, 1.4f);
  EXPECT_EQ(s.objects[3].meshPath, fs::path("/abs/b.ply"));
  EXPECT_EQ(s.objects[3].name, "b");
  EXPECT_EQ(s.ambient, glm::vec3(0.1f));
  EXPECT_EQ(s.background, glm::vec3(0.2f, 0.3f, 0.4f));
  EXPECT_FLOAT_EQ(s.durationS, 4.5f);
  EXPECT_FALSE(s.loop);
}

TEST(Preset, CustomScalarGAndDefaults) {
  const Config c = parse(withObject(
      R"({"mesh": "data:sub/../bunny.ply", "material": {"sigma_s": [1, 1, 1], "sigma_a": [1, 1, 1], "g": -0.3}})"));
  const sss::SceneObject& o = c.scene.objects[0];
  EXPECT_EQ(o.meshPath, fs::path("/data/bunny.ply"));  // normalised
  EXPECT_EQ(o.material.g, glm::vec3(-0.3f));
  EXPECT_FLOAT_EQ(o.material.eta, 1.3f);
  EXPECT_FLOAT_EQ(o.transform.scale, 1.0f);
  EXPECT_EQ(o.albedo, glm::vec3(0.8f));
  EXPECT_TRUE(c.scene.lights.empty());
  EXPECT_EQ(c.scene.name, "p");  // the file's stem
  EXPECT_FLOAT_EQ(c.scene.camera.fovYDeg, 35.0f);
  EXPECT_EQ(c.scene.camera.up, glm::vec3(0, 1, 0));
}

TEST(Preset, UnknownKeysAreLocatedWithSuggestions) {
  EXPECT_EQ(errorOf(withObject(R"({"shape": "sphere", "scael": 2})")),
            "p.json:4:25: unknown key \"scael\" (did you mean \"scale\"?)");
  EXPECT_EQ(errorOf(withObject(R"({"shape": "sphere", "colour": [1, 1, 1]})")), "p.json:4:25: unknown key \"colour\"");
  // The first unknown key in document order, not alphabetical order.
  EXPECT_EQ(errorOf(withObject(R"({"zz": 1, "aa": 2})")), "p.json:4:6: unknown key \"zz\"");
  EXPECT_EQ(errorOf(withCamera(R"("camera": {"position": [0, 0, 1], "target": [0, 0, 0], "fov": 30})")),
            "p.json:3:58: unknown key \"fov\" (did you mean \"fov_deg\"?)");
  EXPECT_EQ(errorOf(withTopLevel(R"("ligths": [])")), "p.json:3:3: unknown key \"ligths\" (did you mean \"lights\"?)");
  // A key of the other light type is unknown for this one.
  EXPECT_EQ(errorOf(withObject(R"({"shape": "sphere"})",
                               ",\n  \"lights\": [{\"type\": \"directional\", \"direction\": [0, 1, 0], "
                               "\"intensity\": [1, 1, 1]}]")),
            "p.json:6:62: unknown key \"intensity\"");
  EXPECT_EQ(errorOf(withObject(R"({"shape": "sphere", "material": {"sigma_s": [1, 1, 1], "sigma_t": [1, 1, 1]}})")),
            "p.json:4:60: unknown key \"sigma_t\" (did you mean \"sigma_s\"?)");
  EXPECT_EQ(errorOf(withObject(R"({"shape": "sphere"})", ",\n  \"animation\": {\"duration\": 2}")),
            "p.json:6:17: unknown key \"duration\" (did you mean \"duration_s\"?)");
}

TEST(Preset, WrongTypesAreLocatedAtTheValue) {
  EXPECT_EQ(errorOf(withObject(R"({"shape": "sphere", "albedo": [1, 1]})")),
            "p.json:4:35: albedo: expected an array of 3 numbers");
  EXPECT_EQ(errorOf(withObject(R"({"shape": "sphere", "albedo": [1, "1", 1]})")),
            "p.json:4:35: albedo: expected an array of 3 numbers");
  EXPECT_EQ(errorOf(withObject(R"({"shape": "sphere", "scale": "big"})")), "p.json:4:34: scale: expected a number");
  EXPECT_EQ(errorOf(withObject(R"({"shape": "sphere", "name": 3})")), "p.json:4:33: name: expected a string");
  EXPECT_EQ(errorOf(withObject(R"({"shape": 3})")), "p.json:4:15: shape: expected a string");
  EXPECT_EQ(errorOf(withObject(R"({"mesh": ["a.ply"]})")), "p.json:4:14: mesh: expected a string (a file name)");
  EXPECT_EQ(errorOf(withObject(R"({"shape": "sphere", "material": 3})")),
            "p.json:4:37: material: expected a name from materials.csv or an object of coefficients");
  EXPECT_EQ(errorOf(withObject(R"("sphere")")), "p.json:4:5: expected an object (an object)");
  EXPECT_EQ(errorOf(withTopLevel(R"("lights": {"type": "point"})")), "p.json:3:13: lights: expected an array");
  EXPECT_EQ(errorOf(withTopLevel(R"("lights": [{"type": "point", "position": [0, 1, 0], "intensity": [1, 1, 1], )"
                                 R"("shadows": "yes"}])")),
            "p.json:3:90: shadows: expected true or false");
  EXPECT_EQ(errorOf(withCamera(R"("camera": [0, 0, 1])")), "p.json:3:13: expected an object (the camera)");
  EXPECT_EQ(errorOf("[1, 2]"), "p.json:1:1: expected an object (a preset)");
  EXPECT_EQ(errorOf(withTopLevel(R"("lights": [3])")), "p.json:3:14: expected an object (a light)");
}

TEST(Preset, OutOfRangeValuesAreLocatedAtTheComponent) {
  EXPECT_EQ(errorOf(withObject(R"({"shape": "sphere", "albedo": [0.5, -0.1, 0.5]})")),
            "p.json:4:41: albedo: -0.1 is out of range [0, 1]");
  EXPECT_EQ(errorOf(withObject(R"({"shape": "sphere", "albedo": [0.5, 0.5, 1.5]})")),
            "p.json:4:46: albedo: 1.5 is out of range [0, 1]");
  EXPECT_EQ(errorOf(withObject(R"({"shape": "sphere", "scale": 0})")),
            "p.json:4:34: scale: 0 is out of range [1e-05, 1000]");
  EXPECT_EQ(errorOf(withObject(R"({"shape": "sphere", "scale": -1})")),
            "p.json:4:34: scale: -1 is out of range [1e-05, 1000]");
  EXPECT_EQ(errorOf(withObject(R"({"shape": "sphere", "scale": 1e300})")),
            "p.json:4:34: scale: 1e+300 is out of range [1e-05, 1000]");
  EXPECT_EQ(errorOf(withObject(R"({"shape": "box", "size": [1, 0, 1]})")),
            "p.json:4:34: size: 0 is out of range (0, 10000]");
  EXPECT_EQ(errorOf(withObject(R"({"shape": "sphere", "position": [0, 0, 1e9]})")),
            "p.json:4:44: position: 1e+09 is out of range [-10000, 10000]");
  EXPECT_EQ(errorOf(withCamera(R"("camera": {"position": [0, 0, 1], "target": [0, 0, 0], "fov_deg": 180})")),
            "p.json:3:69: fov_deg: 180 is out of range [1, 179]");
  EXPECT_EQ(errorOf(withTopLevel(R"("ambient": [0, 0, -1])")), "p.json:3:21: ambient: -1 is out of range [0, 1e+09]");
  EXPECT_EQ(errorOf(withTopLevel(R"("lights": [{"type": "directional", "direction": [0, 1, 0], "irradiance": [-3, 3, 3]}])")),
            "p.json:3:77: irradiance: -3 is out of range [0, 1e+09]");
  EXPECT_EQ(errorOf(withObject(R"({"shape": "sphere"})", ",\n  \"animation\": {\"duration_s\": -1}")),
            "p.json:6:31: duration_s: -1 is out of range [0, 1e+06]");
}

TEST(Preset, GeometricConstraints) {
  EXPECT_EQ(errorOf(withTopLevel(R"("lights": [{"type": "directional", "direction": [0, 0, 0], "irradiance": [3, 3, 3]}])")),
            "p.json:3:51: direction: must not be the zero vector");
  EXPECT_EQ(errorOf(withCamera(R"("camera": {"position": [0, 1, 0], "target": [0, 1, 0]})")),
            "p.json:3:47: target: the same point as the camera position");
  EXPECT_EQ(errorOf(withCamera(R"("camera": {"position": [0, 1, 0], "target": [0, 0, 0]})")),
            "p.json:3:13: up: parallel to the view direction (position → target)");
  EXPECT_EQ(errorOf(withCamera(R"("camera": {"position": [0, 0, 1], "target": [0, 0, 0], "up": [0, 0, 1]})")),
            "p.json:3:64: up: parallel to the view direction (position → target)");
  EXPECT_EQ(errorOf(withCamera(R"("camera": {"position": [0, 0, 1], "target": [0, 0, 0], "height": 1})")),
            "p.json:3:58: \"height\" applies to an orthographic camera (use \"fov_deg\")");
  EXPECT_EQ(errorOf(withCamera(R"("camera": {"type": "ortho", "position": [0, 0, 1], "target": [0, 0, 0]})")),
            "p.json:3:22: type: unknown value \"ortho\" (did you mean \"orthographic\"?); choices: perspective, orthographic");
}

TEST(Preset, ObjectsNeedExactlyOneOfMeshAndShape) {
  EXPECT_EQ(errorOf(withObject(R"({"mesh": "a.ply", "shape": "box"})")),
            "p.json:4:23: an object has \"mesh\" or \"shape\", not both");
  EXPECT_EQ(errorOf(withObject(R"({"albedo": [1, 1, 1]})")),
            "p.json:4:5: an object needs \"mesh\" (a file), \"shape\" or \"field\"");
  EXPECT_EQ(errorOf(withObject(R"({"mesh": "a.ply", "field": {"type": "blob"}})")),
            "p.json:4:23: an object has \"field\", \"mesh\" or \"shape\", only one of them");
  EXPECT_EQ(errorOf(withObject(R"({"field": {"type": "cube"}})")),
            "p.json:4:24: type: unknown value \"cube\"; choices: blob, candle, mesh");
  EXPECT_EQ(errorOf(withObject(R"({"shape": "cone"})")),
            "p.json:4:15: shape: unknown value \"cone\"; choices: plane, sphere, box, hollow-cylinder");
  EXPECT_EQ(errorOf(withObject(R"({"mesh": ""})")), "p.json:4:14: mesh: empty file name");
  EXPECT_EQ(errorOf(withObject(R"({"mesh": "data:"})")),
            "p.json:4:14: mesh: \"data:\" needs a file name relative to the data folder");
  EXPECT_EQ(errorOf(withObject(R"({"mesh": "a.ply", "size": [1, 1, 1]})")),
            "p.json:4:23: \"size\" applies to planes and boxes; a mesh is sized by \"scale\"");
  EXPECT_EQ(errorOf(withObject(R"({"shape": "sphere", "size": [1, 1, 1]})")),
            "p.json:4:25: \"size\" applies to planes and boxes; a sphere is sized by \"scale\"");
  EXPECT_EQ(errorOf(withObject(R"({"shape": "plane", "size": [1, 1, 1]})")),
            "p.json:4:32: size: expected an array of 2 numbers");
}

TEST(Preset, RequiredFields) {
  EXPECT_EQ(errorOf("{\n  \"objects\": [{\"shape\": \"box\"}]\n}"), "p.json:1:1: missing \"camera\"");
  EXPECT_EQ(errorOf("{\"camera\": {\"position\": [0, 0, 1], \"target\": [0, 0, 0]}}"), "p.json:1:1: missing \"objects\"");
  EXPECT_EQ(errorOf(withCamera(R"("camera": {"target": [0, 0, 0]})")), "p.json:3:13: missing \"position\"");
  EXPECT_EQ(errorOf("{\"camera\": {\"position\": [0, 0, 1], \"target\": [0, 0, 0]},\n \"objects\": []}"),
            "p.json:2:13: objects: a preset needs at least one object");
  EXPECT_EQ(errorOf(withTopLevel(R"("lights": [{"direction": [0, 1, 0]}])")), "p.json:3:14: missing \"type\"");
  EXPECT_EQ(errorOf(withTopLevel(R"("lights": [{"type": "point", "intensity": [1, 1, 1]}])")),
            "p.json:3:14: missing \"position\"");
  EXPECT_EQ(errorOf(withObject(R"({"shape": "sphere", "material": {"sigma_s": [1, 1, 1]}})")),
            "p.json:4:37: missing \"sigma_a\"");
}

TEST(Preset, Materials) {
  EXPECT_EQ(errorOf(withObject(R"({"shape": "sphere", "material": "Marbel"})")),
            "p.json:4:37: unknown material \"Marbel\" (did you mean \"Marble\"?)");
  EXPECT_EQ(errorOf(withObject(R"({"shape": "sphere", "material": "Granite"})")),
            "p.json:4:37: unknown material \"Granite\"");
  // Invalid coefficients: located at the material value, named as in materials.csv.
  EXPECT_EQ(errorOf(withObject(R"({"shape": "sphere", "material": {"sigma_s": [1, 1, 1], "sigma_a": [0, -1, 0]}})")),
            "p.json:4:37: invalid material: sigma_a_g is negative (-1)");
  EXPECT_EQ(errorOf(withObject(R"({"shape": "sphere", "material": {"sigma_s": [1, 1, 1], "sigma_a": [0, 0, 0], "g": 1}})")),
            "p.json:4:37: invalid material: g_r = 1 is not in (-1, 1)");
  EXPECT_EQ(errorOf(withObject(R"({"shape": "sphere", "material": {"sigma_s": [1, 1, 0], "sigma_a": [0, 0, 0]}})")),
            "p.json:4:37: invalid material: sigma_s_b + sigma_a_b is 0 (nothing scatters or absorbs)");
  EXPECT_EQ(errorOf(withObject(R"({"shape": "sphere", "material": {"sigma_s": [1, 1, 1], "sigma_a": [0, 0, 0], "eta": 0}})")),
            "p.json:4:37: invalid material: eta must be a positive number (0)");
}

TEST(Preset, AMaterialInOpenPbrTerms) {
  // Issue 42, point 3: subsurface_color, subsurface_radius_mm, subsurface_radius_scale, eta (and g)
  // become σ_a and σ_s (sss/bssrdf/subsurface_appearance.h: 1/σ_t' is the radius of each band).
  const Config c = parse(withObject(
      R"({"shape": "sphere", "material": {"subsurface_color": [0.8, 0.5, 0.2], "subsurface_radius_mm": 2,
          "subsurface_radius_scale": [1, 0.5, 0.25], "eta": 1.4}})"));
  const sss::Material& m = c.scene.objects[0].material;
  EXPECT_EQ(m.name, "custom (subsurface colour)");
  EXPECT_FLOAT_EQ(m.eta, 1.4f);
  EXPECT_NEAR(1.0 / (m.sigma_a.b + m.sigma_s.b), 0.5, 1e-6);  // g = 0: σ_t' = σ_t
  // Errors at the value, one line, as the coefficients' are (column 64: the "1.5", 4 columns of
  // indentation before the object).
  EXPECT_EQ(errorOf(withObject(R"({"shape": "sphere", "material": {"subsurface_color": [0.8, 1.5, 0.2], "subsurface_radius_mm": 2}})")),
            "p.json:4:64: subsurface_color: 1.5 is out of range [0, 1]");
  EXPECT_EQ(errorOf(withObject(R"({"shape": "sphere", "material": {"subsurface_color": [0.8, 0.5, 0.2]}})")),
            "p.json:4:37: missing \"subsurface_radius_mm\"");
  EXPECT_NE(errorOf(withObject(R"({"shape": "sphere", "material": {"subsurface_color": [0.8, 0.5, 0.2], "subsurface_radius_mm": 2, "sigma_a": [1, 1, 1]}})"))
                .find("unknown key"),
            std::string::npos);
}

TEST(Preset, AnimationStartTime) {
  EXPECT_FLOAT_EQ(parse(withObject(R"({"shape": "sphere"})", R"(, "animation": {"duration_s": 20, "start_s": 12})"))
                      .scene.startS,
                  12.0f);
  EXPECT_FLOAT_EQ(parse(withObject(R"({"shape": "sphere"})")).scene.startS, 0.0f);
  EXPECT_NE(errorOf(withObject(R"({"shape": "sphere"})", R"(, "animation": {"start_s": -1})")).find("start_s"),
            std::string::npos);
}

TEST(Preset, AMaterialFromAMeasuredOneScaled) {
  // "from" copies a row of materials.csv; "scale" multiplies σ_s and σ_a (the mean free paths shrink
  // by that factor, the albedo, g and η stay); keys given beside "from" replace the row's values.
  const Config c = parse(withObject(R"({"shape": "sphere", "material": {"from": "Marble", "scale": 10}})"));
  const sss::Material& m = c.scene.objects[0].material;
  EXPECT_FLOAT_EQ(m.sigma_s.g, 26.2f);
  EXPECT_FLOAT_EQ(m.sigma_a.b, 0.071f);
  EXPECT_FLOAT_EQ(m.eta, 1.5f);
  EXPECT_EQ(m.name, "Marble x10");
  const Config d = parse(withObject(R"({"shape": "sphere", "material": {"from": "Ketchup", "g": 0.5, "eta": 1.4}})"));
  EXPECT_FLOAT_EQ(d.scene.objects[0].material.sigma_s.r, 0.18f);
  EXPECT_FLOAT_EQ(d.scene.objects[0].material.g.b, 0.5f);
  EXPECT_FLOAT_EQ(d.scene.objects[0].material.eta, 1.4f);
  EXPECT_EQ(d.scene.objects[0].material.name, "Ketchup");
  EXPECT_EQ(errorOf(withObject(R"({"shape": "sphere", "material": {"from": "Marbel", "scale": 2}})")),
            "p.json:4:46: unknown material \"Marbel\" (did you mean \"Marble\"?)");
  EXPECT_EQ(errorOf(withObject(R"({"shape": "sphere", "material": {"from": "Marble", "scale": 0}})")).substr(0, 12),
            "p.json:4:65:");
  EXPECT_EQ(errorOf(withObject(R"({"shape": "sphere", "material": {"sigma_s": [1, 1, 1], "sigma_a": [0, 0, 0], "scale": 2}})")),
            "p.json:4:82: \"scale\" applies to a material given \"from\" a measured one");
}

TEST(Preset, AVolumeInsideATranslucentObject) {
  // "volume": a second material in layers or veins (SSLPV's heterogeneous medium), every key checked.
  const std::string good =
      R"({"shape": "sphere", "material": "Marble", "volume": {"material": "Ketchup", "period": 0.02, )"
      R"("fraction": 0.25, "turbulence": 1.5, "seed": 4, "axis": [0, 0, 2]}})";
  const Config c = parse(withObject(good));
  ASSERT_TRUE(c.scene.objects[0].volume.has_value());
  const sss::MaterialVolume& v = *c.scene.objects[0].volume;
  EXPECT_EQ(v.material.name, "Ketchup");
  EXPECT_FLOAT_EQ(v.period, 0.02f);
  EXPECT_FLOAT_EQ(v.fraction, 0.25f);
  EXPECT_FLOAT_EQ(v.turbulence, 1.5f);
  EXPECT_EQ(v.seed, 4u);
  EXPECT_FLOAT_EQ(v.axis.z, 1.0f);  // normalised
  const auto defaults = parse(withObject(R"({"shape": "sphere", "material": "Marble", "volume": {"material": "Ketchup", "period": 1}})"));
  EXPECT_FLOAT_EQ(defaults.scene.objects[0].volume->fraction, 0.5f);
  EXPECT_FLOAT_EQ(defaults.scene.objects[0].volume->axis.y, 1.0f);
  EXPECT_FALSE(parse(withObject(R"({"shape": "sphere", "material": "Marble"})")).scene.objects[0].volume.has_value());
  // Errors, located at the key or value (line 4; the object starts at column 5).
  const auto at = [](const std::string& object, const std::string& needle) {
    return "p.json:4:" + std::to_string(5 + object.find(needle)) + ": ";
  };
  const std::string misspelt = R"({"shape": "sphere", "material": "Marble", "volume": {"material": "Ketchup", "perid": 1}})";
  EXPECT_EQ(errorOf(withObject(misspelt)), at(misspelt, "\"perid\"") + "unknown key \"perid\" (did you mean \"period\"?)");
  const std::string opaque = R"({"shape": "sphere", "volume": {"material": "Ketchup", "period": 1}})";
  EXPECT_EQ(errorOf(withObject(opaque)).substr(0, at(opaque, "\"volume\"").size() + 10),
            at(opaque, "\"volume\"") + "\"volume\" i");
  const std::string missing = R"({"shape": "sphere", "material": "Marble", "volume": {"material": "Ketchup"}})";
  EXPECT_EQ(errorOf(withObject(missing)), at(missing, "{\"material\": \"Ketchup\"") + "missing \"period\"");
  const std::string fraction = R"({"shape": "sphere", "material": "Marble", "volume": {"material": "Ketchup", "period": 1, "fraction": 2}})";
  EXPECT_EQ(errorOf(withObject(fraction)), at(fraction, "2}") + "fraction: 2 is out of range [0, 1]");
  const std::string seed = R"({"shape": "sphere", "material": "Marble", "volume": {"material": "Ketchup", "period": 1, "seed": -1}})";
  EXPECT_EQ(errorOf(withObject(seed)), at(seed, "-1") + "seed: expected an integer in [0, 4294967295]");
  const std::string inner = R"({"shape": "sphere", "material": "Marble", "volume": {"material": "Marbel", "period": 1}})";
  EXPECT_EQ(errorOf(withObject(inner)), at(inner, "\"Marbel\"") + "unknown material \"Marbel\" (did you mean \"Marble\"?)");
}

TEST(Preset, SettingsGoThroughTheRegistry) {
  EXPECT_EQ(errorOf(withTopLevel(R"("settings": {"render.width": 0})")),
            "p.json:3:32: render.width: 0 is out of range [1, 16384]");
  EXPECT_EQ(errorOf(withTopLevel(R"("settings": {"render.widht": 10})")),
            "p.json:3:16: unknown parameter \"render.widht\" (did you mean \"render.width\"?)");
  EXPECT_EQ(errorOf(withTopLevel(R"("settings": {"material": "Marbel"})")),
            "p.json:3:28: material: unknown value \"Marbel\" (did you mean \"Marble\"?); choices: Marble, Ketchup");
  EXPECT_EQ(errorOf(withTopLevel(R"("settings": {"light.direction": [0, 1, 0]})")),
            "p.json:3:35: light.direction: the scene has no lights");
  EXPECT_EQ(errorOf(withTopLevel(R"("settings": [1])")), "p.json:3:15: settings: expected an object of parameter values");
  // Applied in document order: the first error in the file is the one reported.
  EXPECT_EQ(errorOf(withTopLevel(R"("settings": {"render.width": -1, "render.height": -1})")),
            "p.json:3:32: render.width: -1 is out of range [1, 16384]");
}

TEST(Preset, SyntaxErrorsAndDuplicatesKeepTheirLocation) {
  EXPECT_EQ(errorOf(withObject(R"({"shape": "sphere", "shape": "box"})")), "p.json:4:25: duplicate key \"shape\"");
  const std::string e = errorOf(withObject(R"({"shape": "sphere",})"));
  EXPECT_EQ(e.rfind("p.json:4:24: syntax error", 0), 0u) << e;
}

TEST(Preset, LoadNamesTheFileAsGiven) {
  const sss::MaterialTable materials = sss::MaterialTable::load(kDataDir / "materials.csv");
  try {
    loadPreset("/nonexistent/x.json", materials, kDataDir);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "/nonexistent/x.json: cannot open");
  }
}

}  // namespace
}  // namespace tallow::app
