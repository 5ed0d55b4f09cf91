#include "app/config/preset.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "app/config/input_error.h"
#include "app/config/json_document.h"
#include "app/config/params.h"
#include "app/config/registry.h"
#include "geometry/candle_field.h"
#include "gpu/utf8.h"
#include "sss/bssrdf/subsurface_appearance.h"

namespace tallow::app {

namespace fs = std::filesystem;

namespace {

using json = nlohmann::json;
using Ptr = JsonDocument::Pointer;

/// An accepted interval of numbers; `minOpen` excludes the minimum (for sizes that must be > 0).
struct Range {
  double min, max;
  bool minOpen = false;

  bool contains(double v) const { return (minOpen ? v > min : v >= min) && v <= max; }
  std::string str() const {
    return (minOpen ? "(" : "[") + formatNumber(min) + ", " + formatNumber(max) + "]";
  }
};

// Ranges of preset fields that have no registry parameter of their own. Finite and well inside a
// float, so no value overflows when it is stored.
constexpr Range kAlbedo{0.0, 1.0};
constexpr Range kExtent{0.0, 1e4, true};           ///< plane and box sizes (× scale), metres
constexpr Range kDirection{-1e6, 1e6};             ///< any length; normalised after reading
constexpr Range kAngleDeg{-1e6, 1e6};              ///< Euler angles
constexpr Range kOrthoHeight{0.0, 1e4, true};      ///< metres
constexpr Range kDurationS{0.0, 1e6};              ///< animation length, seconds
constexpr Range kCoefficient{-1e6, 1e6};           ///< σ_s, σ_a [mm⁻¹]; sign checked by validateMaterial
constexpr Range kAnisotropy{-1e6, 1e6};            ///< g; |g| < 1 checked by validateMaterial
constexpr Range kEta{-1e6, 1e6};                   ///< η > 0 checked by validateMaterial
constexpr float kDefaultEta = 1.3f;                ///< as most rows of materials.csv

const std::vector<std::string> kTopKeys = {"name",    "description", "camera",    "lights",   "objects",
                                           "ambient", "background",  "animation", "settings", "environment",
                                           "map_directions"};
const std::vector<std::string> kCameraKeys = {"type", "position", "target", "up", "fov_deg", "height"};
const std::vector<std::string> kDirectionalKeys = {"type", "direction", "irradiance", "shadows"};
const std::vector<std::string> kPointKeys = {"type", "position", "follow", "intensity", "shadows"};
const std::vector<std::string> kObjectKeys = {"name",     "mesh",     "shape",        "size",  "material",
                                              "albedo",   "position", "rotation_deg", "scale", "field",
                                              "volume",   "pool_material"};
const std::vector<std::string> kBlobFieldKeys = {"type", "scale"};
const std::vector<std::string> kCandleFieldKeys = {"type", "duration_s", "time_scale", "drips", "seed"};
const std::vector<std::string> kMeshFieldKeys = {"type", "mesh", "melt_s"};
constexpr Range kBlobScale{0.0, 1e3, true};      ///< metres per unscaled blob unit
constexpr Range kCandleDurationS{0.0, 1e6, true};  ///< animation seconds of the candle's burn
constexpr Range kCandleTimeScale{1.0, 3600.0, false};  ///< real seconds per animation second
constexpr Range kMeltDurationS{0.0, 1e6, true};    ///< seconds until a mesh field has melted
const std::vector<std::string> kMaterialKeys = {"sigma_s", "sigma_a", "g", "eta", "from", "scale"};
/// A material in OpenPBR's terms (sss/bssrdf/subsurface_appearance.h).
const std::vector<std::string> kAppearanceKeys = {"subsurface_color", "subsurface_radius_mm", "subsurface_radius_scale",
                                                  "eta", "g"};
constexpr Range kSubsurfaceColor{0.0, 1.0};           ///< total diffuse reflectance per band
constexpr Range kSubsurfaceRadiusMm{0.0, 1e6, true};  ///< mean free path [mm]
constexpr Range kSubsurfaceRadiusScale{0.0, 1e6, true};
constexpr Range kMaterialScale{0.0, 1e6, true};  ///< multiplies σ_s and σ_a of a "from" material
const std::vector<std::string> kAnimationKeys = {"duration_s", "loop", "start_s"};
const std::vector<std::string> kVolumeKeys = {"material", "axis", "period", "fraction", "turbulence", "seed"};
constexpr Range kVolumePeriod{0.0, 1e4, true};  ///< metres between layers of a "volume"
constexpr Range kVolumeFraction{0.0, 1.0};      ///< share of a period in the second material
constexpr Range kVolumeTurbulence{0.0, 1e3};    ///< periods the layers wander

/// Walks one preset document and fills a Config. Every accessor checks type and range and throws
/// InputError located at the offending value (or key, for unknown keys).
class PresetReader {
 public:
  PresetReader(const JsonDocument& doc, const Registry& registry, const sss::MaterialTable& materials,
               fs::path presetDir, fs::path dataDir)
      : doc_(doc), registry_(registry), materials_(materials), presetDir_(std::move(presetDir)),
        dataDir_(std::move(dataDir)) {}

  Config read() {
    Config config;
    registry_.applyDefaults(config);
    sss::Scene& scene = config.scene;
    const Ptr root;
    checkKeys(root, kTopKeys, "a preset");

    scene.name = optString(root, "name").value_or(fs::path(doc_.fileName()).stem().string());
    scene.description = optString(root, "description").value_or("");
    readCamera(require(root, "camera"), scene.camera);
    if (has(root, "lights")) {
      const Ptr lights = root / "lights";
      expectArray(lights);
      for (std::size_t i = 0; i < at(lights).size(); ++i) scene.lights.push_back(readLight(lights / i));
    }
    const Ptr objects = require(root, "objects");
    expectArray(objects);
    if (at(objects).empty()) doc_.fail(objects, "objects: a preset needs at least one object");
    for (std::size_t i = 0; i < at(objects).size(); ++i) scene.objects.push_back(readObject(objects / i));
    if (has(root, "lights")) resolveFollows(root / "lights", scene);
    if (has(root, "environment")) scene.environment = readEnvironment(root / "environment");
    if (has(root, "map_directions")) {
      // The radiosity maps' camera directions, instead of Halton's (the paper, §3.2).
      const Ptr list = root / "map_directions";
      expectArray(list);
      if (at(list).empty() || at(list).size() > 256)
        doc_.fail(list, "map_directions: expected 1 to 256 directions");
      for (std::size_t i = 0; i < at(list).size(); ++i) scene.mapDirections.push_back(direction(list / i, "map_directions"));
    }
    scene.ambient = optVec3(root, "ambient", paramRange("ambient")).value_or(glm::vec3(0.0f));
    scene.background = optVec3(root, "background", paramRange("ambient")).value_or(glm::vec3(0.0f));
    if (has(root, "animation")) {
      const Ptr animation = root / "animation";
      checkKeys(animation, kAnimationKeys, "animation");
      scene.durationS = optNumber(animation, "duration_s", kDurationS).value_or(0.0f);
      scene.loop = optBool(animation, "loop").value_or(true);
      scene.startS = optNumber(animation, "start_s", kDurationS).value_or(0.0f);
    }
    if (has(root, "settings")) applySettings(root / "settings", config);
    return config;
  }

 private:
  const json& at(const Ptr& p) const { return doc_.root().at(p); }
  bool has(const Ptr& object, const std::string& key) const { return at(object).contains(key); }

  Range paramRange(std::string_view key) const {
    const Registry::Param* p = registry_.find(key);
    if (!p) throw std::logic_error("no parameter " + std::string(key));
    return {p->min, p->max};
  }

  void expectArray(const Ptr& p) const {
    if (!at(p).is_array()) doc_.fail(p, label(p) + "expected an array");
  }

  /// "albedo: " — the key (or index) of `p`, to start a message.
  static std::string label(const Ptr& p) { return p.empty() ? std::string() : p.back() + ": "; }

  /// The member `key` of the object at `object`, or an error at the object naming what is missing.
  Ptr require(const Ptr& object, const std::string& key) const {
    if (!has(object, key)) doc_.fail(object, "missing " + quote(key));
    return object / key;
  }

  /// `object` must be a JSON object whose keys are all in `allowed`; the first unknown key in
  /// document order is reported.
  void checkKeys(const Ptr& object, const std::vector<std::string>& allowed, std::string_view what) const {
    if (!at(object).is_object()) doc_.fail(object, "expected an object (" + std::string(what) + ")");
    for (const std::string& key : doc_.keysInOrder(object))
      if (std::find(allowed.begin(), allowed.end(), key) == allowed.end())
        doc_.failAtKey(object / key, "unknown key " + quote(key) + didYouMean(key, allowed));
  }

  std::optional<std::string> optString(const Ptr& object, const std::string& key) const {
    if (!has(object, key)) return std::nullopt;
    const Ptr p = object / key;
    if (!at(p).is_string()) doc_.fail(p, key + ": expected a string");
    return at(p).get<std::string>();
  }

  std::optional<bool> optBool(const Ptr& object, const std::string& key) const {
    if (!has(object, key)) return std::nullopt;
    const Ptr p = object / key;
    if (!at(p).is_boolean()) doc_.fail(p, key + ": expected true or false");
    return at(p).get<bool>();
  }

  /// A number at `p` within `range`; `name` starts the message.
  float number(const Ptr& p, const std::string& name, const Range& range) const {
    if (!at(p).is_number()) doc_.fail(p, name + ": expected a number");
    const double v = at(p).get<double>();
    if (!range.contains(v)) doc_.fail(p, name + ": " + formatNumber(v) + " is out of range " + range.str());
    return static_cast<float>(v);
  }

  std::optional<float> optNumber(const Ptr& object, const std::string& key, const Range& range) const {
    if (!has(object, key)) return std::nullopt;
    return number(object / key, key, range);
  }

  /// An integer in [min, max] (a number with a fraction is refused, not rounded).
  std::optional<std::int64_t> optInteger(const Ptr& object, const std::string& key, std::int64_t min,
                                         std::int64_t max) const {
    if (!has(object, key)) return std::nullopt;
    const Ptr p = object / key;
    const json& v = at(p);
    const bool fits = v.is_number_integer() &&
                      (v.is_number_unsigned() ? v.get<std::uint64_t>() <= static_cast<std::uint64_t>(max)
                                              : v.get<std::int64_t>() >= min && v.get<std::int64_t>() <= max);
    if (!fits) doc_.fail(p, key + ": expected an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "]");
    return v.is_number_unsigned() ? static_cast<std::int64_t>(v.get<std::uint64_t>()) : v.get<std::int64_t>();
  }

  /// A random seed: an integer in [0, 2³² − 1].
  std::optional<std::uint32_t> optSeed(const Ptr& object, const std::string& key) const {
    const auto v = optInteger(object, key, 0, 0xFFFFFFFFll);
    if (!v) return std::nullopt;
    return static_cast<std::uint32_t>(*v);
  }

  /// An array of `n` numbers, each within `range`; out-of-range errors point at the element.
  std::vector<float> numbers(const Ptr& p, const std::string& name, std::size_t n, const Range& range) const {
    const json& v = at(p);
    if (!v.is_array() || v.size() != n || !std::all_of(v.begin(), v.end(), [](const json& c) { return c.is_number(); }))
      doc_.fail(p, name + ": expected an array of " + std::to_string(n) + " numbers");
    std::vector<float> out;
    for (std::size_t i = 0; i < n; ++i) out.push_back(number(p / i, name, range));
    return out;
  }

  glm::vec3 vec3(const Ptr& p, const std::string& name, const Range& range) const {
    const std::vector<float> v = numbers(p, name, 3, range);
    return {v[0], v[1], v[2]};
  }

  std::optional<glm::vec3> optVec3(const Ptr& object, const std::string& key, const Range& range) const {
    if (!has(object, key)) return std::nullopt;
    return vec3(object / key, key, range);
  }

  /// A string that must be one of `choices`.
  std::string choice(const Ptr& p, const std::string& name, const std::vector<std::string>& choices) const {
    if (!at(p).is_string()) doc_.fail(p, name + ": expected a string");
    const std::string s = at(p).get<std::string>();
    if (std::find(choices.begin(), choices.end(), s) == choices.end()) {
      std::string list;
      for (const std::string& c : choices) list += (list.empty() ? "" : ", ") + c;
      doc_.fail(p, name + ": unknown value " + quote(s) + didYouMean(s, choices) + "; choices: " + list);
    }
    return s;
  }

  /// A direction of any non-zero length, normalised (in double: a tiny float vector's squared
  /// length would underflow to 0).
  glm::vec3 direction(const Ptr& p, const std::string& name) const {
    const glm::dvec3 d(vec3(p, name, kDirection));
    if (d == glm::dvec3(0.0)) doc_.fail(p, name + ": must not be the zero vector");
    return glm::vec3(d / glm::length(d));
  }

  /// Scene coordinates share the bounds of the camera position parameter.
  Range coordinates() const { return paramRange("camera.position"); }

  void readCamera(const Ptr& p, sss::Camera& camera) const {
    checkKeys(p, kCameraKeys, "the camera");
    camera.orthographic =
        has(p, "type") && choice(p / "type", "type", {"perspective", "orthographic"}) == "orthographic";
    camera.position = vec3(require(p, "position"), "position", paramRange("camera.position"));
    camera.target = vec3(require(p, "target"), "target", paramRange("camera.target"));
    const glm::dvec3 view = glm::dvec3(camera.target) - glm::dvec3(camera.position);
    constexpr double kMinViewDistance = 1e-6;  // metres; a micrometre is far below any scene's scale
    if (glm::length(view) < kMinViewDistance) doc_.fail(p / "target", "target: the same point as the camera position");
    camera.up = has(p, "up") ? direction(p / "up", "up") : glm::vec3(0.0f, 1.0f, 0.0f);
    constexpr double kMinSinViewUp = 1e-3;  // below this the camera's roll is ill-defined
    if (glm::length(glm::cross(glm::normalize(view), glm::dvec3(camera.up))) < kMinSinViewUp)
      doc_.fail(has(p, "up") ? p / "up" : p, "up: parallel to the view direction (position → target)");
    if (has(p, "fov_deg")) {
      if (camera.orthographic) doc_.failAtKey(p / "fov_deg", "\"fov_deg\" applies to a perspective camera (use \"height\")");
      camera.fovYDeg = number(p / "fov_deg", "fov_deg", paramRange("camera.fov_deg"));
    }
    if (has(p, "height")) {
      if (!camera.orthographic) doc_.failAtKey(p / "height", "\"height\" applies to an orthographic camera (use \"fov_deg\")");
      camera.orthoHeight = number(p / "height", "height", kOrthoHeight);
    }
  }

  sss::Light readLight(const Ptr& p) const {
    if (!at(p).is_object()) doc_.fail(p, "expected an object (a light)");
    sss::Light light;
    const std::string type = choice(require(p, "type"), "type", {"directional", "point"});
    const Range intensity = paramRange("light.intensity");
    if (type == "directional") {
      checkKeys(p, kDirectionalKeys, "a directional light");
      light.kind = sss::LightKind::Directional;
      light.direction = direction(require(p, "direction"), "direction");
      light.intensity = vec3(require(p, "irradiance"), "irradiance", intensity);
    } else {
      checkKeys(p, kPointKeys, "a point light");
      light.kind = sss::LightKind::Point;
      if (has(p, "follow")) {
        if (has(p, "position"))
          doc_.failAtKey(p / "position", "a light that follows a flame has no \"position\"; it sits at the flame");
        if (!at(p / "follow").is_string()) doc_.fail(p / "follow", "follow: expected the name of a candle field object");
      } else {
        light.position = vec3(require(p, "position"), "position", paramRange("light.position"));
      }
      light.intensity = vec3(require(p, "intensity"), "intensity", intensity);
    }
    light.castsShadows = optBool(p, "shadows").value_or(true);
    return light;
  }

  /// "environment": {"file": "data:env.hdr", "lights": 16, "rotation_deg": 0, "intensity": 1}, a
  /// Radiance .hdr lat-long map turned into directional lights by app/config/setup.cpp (see
  /// sss/maps/environment_lights.h). The file must exist (checked here); its content is read at load.
  sss::Environment readEnvironment(const Ptr& p) const {
    static const std::vector<std::string> kEnvironmentKeys = {"file", "lights", "rotation_deg", "intensity"};
    checkKeys(p, kEnvironmentKeys, "the environment");
    sss::Environment env;
    const Ptr file = require(p, "file");
    if (!at(file).is_string()) doc_.fail(file, "file: expected a string (a Radiance .hdr file name)");
    const std::string text = at(file).get<std::string>();
    constexpr std::string_view kDataPrefix = "data:";
    fs::path path;
    if (text.rfind(kDataPrefix, 0) == 0) {
      path = fs::path(text.substr(kDataPrefix.size()));
      if (path.empty() || path.is_absolute()) doc_.fail(file, "file: \"data:\" needs a file name relative to the data folder");
      path = dataDir_ / path;
    } else {
      path = fs::path(text);
      if (path.empty()) doc_.fail(file, "file: empty file name");
      if (path.is_relative()) path = presetDir_ / path;
    }
    env.file = fs::absolute(path).lexically_normal();
    std::error_code ec;
    if (!fs::is_regular_file(env.file, ec)) doc_.fail(file, "file: no such file " + quote(env.file.string()));
    if (has(p, "lights")) {
      const Ptr lights = p / "lights";
      constexpr int kMaxLights = 32;  // the renderer's limit of directional lights
      const json& v = at(lights);
      if (!v.is_number_integer()) doc_.fail(lights, "lights: expected an integer");
      const bool inRange = v.is_number_unsigned() ? v.get<std::uint64_t>() >= 1 && v.get<std::uint64_t>() <= kMaxLights
                                                  : v.get<std::int64_t>() >= 1 && v.get<std::int64_t>() <= kMaxLights;
      if (!inRange)
        doc_.fail(lights, "lights: " + formatNumber(v.get<double>()) + " is out of range [1, " + std::to_string(kMaxLights) + "]");
      env.lights = v.get<int>();
    }
    env.rotationDeg = optNumber(p, "rotation_deg", kAngleDeg).value_or(0.0f);
    const Range intensity = paramRange("light.intensity");
    env.scale = optNumber(p, "intensity", intensity).value_or(1.0f);
    return env;
  }

  /// "follow": "<name>" of point lights → the index of that object, which must be a candle field.
  void resolveFollows(const Ptr& lights, sss::Scene& scene) const {
    for (std::size_t i = 0; i < scene.lights.size(); ++i) {
      const Ptr p = lights / i;
      if (!has(p, "follow")) continue;
      const std::string name = at(p / "follow").get<std::string>();
      const auto it = std::find_if(scene.objects.begin(), scene.objects.end(),
                                   [&](const sss::SceneObject& o) { return o.name == name; });
      if (it == scene.objects.end()) doc_.fail(p / "follow", "follow: no object is named \"" + name + "\"");
      if (it->shape != sss::ShapeKind::Field || it->field.kind != sss::FieldKind::Candle)
        doc_.fail(p / "follow", "follow: \"" + name + "\" is not a candle field; only a candle has a flame to follow");
      scene.lights[i].follow = static_cast<int>(it - scene.objects.begin());
    }
  }

  sss::SceneObject readObject(const Ptr& p) const {
    checkKeys(p, kObjectKeys, "an object");
    sss::SceneObject object;
    const bool isMesh = has(p, "mesh");
    const bool isField = has(p, "field");
    if (isMesh && has(p, "shape")) doc_.failAtKey(p / "shape", "an object has \"mesh\" or \"shape\", not both");
    if (isField && (isMesh || has(p, "shape")))
      doc_.failAtKey(p / "field", "an object has \"field\", \"mesh\" or \"shape\", only one of them");
    if (!isMesh && !isField && !has(p, "shape"))
      doc_.fail(p, "an object needs \"mesh\" (a file), \"shape\" or \"field\"");

    if (isField) {
      object.shape = sss::ShapeKind::Field;
      object.field = readField(p / "field");
      object.name = object.field.kind == sss::FieldKind::Blob     ? "blob"
                    : object.field.kind == sss::FieldKind::Candle ? "candle"
                                                                  : object.field.meshPath.stem().string();
      if (object.field.kind != sss::FieldKind::Mesh && has(p, "scale"))
        doc_.failAtKey(p / "scale", "\"scale\" applies to mesh fields; a blob is sized by its field's \"scale\", a "
                                    "candle is fixed");
    } else if (isMesh) {
      object.shape = sss::ShapeKind::Mesh;
      object.meshPath = meshPath(p / "mesh");
      object.name = object.meshPath.stem().string();
    } else {
      const std::string shape = choice(p / "shape", "shape", {"plane", "sphere", "box", "hollow-cylinder"});
      object.shape = shape == "plane"             ? sss::ShapeKind::Plane
                     : shape == "box"             ? sss::ShapeKind::Box
                     : shape == "hollow-cylinder" ? sss::ShapeKind::HollowCylinder
                                                  : sss::ShapeKind::Sphere;
      object.name = shape;
      if (object.shape == sss::ShapeKind::HollowCylinder) {
        // size = [inner radius, outer radius, height]; the bottom is as thick as the wall.
        const Ptr size = require(p, "size");
        object.size = vec3(size, "size", kExtent);
        if (!(object.size.x < object.size.y))
          doc_.fail(size, "size: a hollow cylinder's inner radius (first) must be less than its outer radius (second)");
        if (!(object.size.z > object.size.y - object.size.x))
          doc_.fail(size, "size: a hollow cylinder's height (third) must exceed its wall thickness (outer − inner "
                          "radius), which is also the thickness of its bottom");
      }
    }
    if (has(p, "size")) {
      const Ptr size = p / "size";
      if (object.shape == sss::ShapeKind::Plane) {
        const std::vector<float> xz = numbers(size, "size", 2, kExtent);
        object.size = {xz[0], 1.0f, xz[1]};
      } else if (object.shape == sss::ShapeKind::Box) {
        object.size = vec3(size, "size", kExtent);
      } else if (object.shape == sss::ShapeKind::HollowCylinder) {
        // read with the shape, above
      } else {
        doc_.failAtKey(size, "\"size\" applies to planes and boxes; " +
                                 std::string(isField ? "a field" : isMesh ? "a mesh" : "a sphere") +
                                 " is sized by \"scale\"");
      }
    }
    object.name = optString(p, "name").value_or(object.name);
    if (has(p, "material")) {
      object.material = readMaterial(p / "material");
      object.translucent = true;
    }
    if (has(p, "volume")) {
      if (!object.translucent)
        doc_.failAtKey(p / "volume", "\"volume\" is a second material inside a translucent object; give the object a "
                                     "\"material\" first");
      object.volume = readVolume(p / "volume");
    }
    if (has(p, "pool_material")) {
      // The liquid of a candle's melt pool (sss/translucent_slots.h): only a candle has one.
      if (!isField || object.field.kind != sss::FieldKind::Candle)
        doc_.failAtKey(p / "pool_material", "\"pool_material\" is the liquid of a candle's melt pool; this object is "
                                            "not a candle field");
      if (!object.translucent)
        doc_.failAtKey(p / "pool_material", "\"pool_material\" needs a translucent candle; give the object a "
                                            "\"material\" first");
      object.liquidMaterial = readMaterial(p / "pool_material");
    }
    object.albedo = optVec3(p, "albedo", kAlbedo).value_or(object.albedo);
    object.transform.position = optVec3(p, "position", coordinates()).value_or(glm::vec3(0.0f));
    object.transform.rotationDeg = optVec3(p, "rotation_deg", kAngleDeg).value_or(glm::vec3(0.0f));
    object.transform.scale = optNumber(p, "scale", paramRange("scale")).value_or(1.0f);
    return object;
  }

  /// "field": {"type": "blob" | "candle" | "mesh", …}; the keys allowed depend on the type.
  sss::FieldDesc readField(const Ptr& p) const {
    if (!at(p).is_object()) doc_.fail(p, "field: expected an object with a \"type\"");
    sss::FieldDesc field;
    const std::string type = choice(require(p, "type"), "type", {"blob", "candle", "mesh"});
    if (type == "blob") {
      checkKeys(p, kBlobFieldKeys, "a blob field");
      field.kind = sss::FieldKind::Blob;
      field.blobScale = optNumber(p, "scale", kBlobScale).value_or(static_cast<float>(field.blobScale));
    } else if (type == "candle") {
      checkKeys(p, kCandleFieldKeys, "a candle field");
      field.kind = sss::FieldKind::Candle;
      field.candleDurationS = optNumber(p, "duration_s", kCandleDurationS).value_or(static_cast<float>(field.candleDurationS));
      field.candleTimeScale = optNumber(p, "time_scale", kCandleTimeScale).value_or(static_cast<float>(field.candleTimeScale));
      field.candleDrips = static_cast<int>(
          optInteger(p, "drips", 0, geometry::CandleParams::kMaxDrips).value_or(field.candleDrips));
      field.candleSeed = optSeed(p, "seed").value_or(field.candleSeed);
    } else {
      checkKeys(p, kMeshFieldKeys, "a mesh field");
      field.kind = sss::FieldKind::Mesh;
      const Ptr mesh = require(p, "mesh");
      field.meshPath = meshPath(mesh);
      field.meltDurationS = optNumber(p, "melt_s", kMeltDurationS).value_or(0.0f);
      // MODELS.md: Stanford asks that the Dragon not be animated, morphed, boolean-processed or
      // shown damaged; a level set is the path to melting, so it is refused here.
      if (field.meshPath.filename() == "dragon.ply")
        doc_.fail(mesh, "mesh: dragon.ply cannot be a field: Stanford's terms for the Dragon forbid animating, "
                        "morphing, boolean-processing or showing it damaged (see data/MODELS.md); use it as a "
                        "static \"mesh\" object instead");
    }
    return field;
  }

  fs::path meshPath(const Ptr& p) const {
    if (!at(p).is_string()) doc_.fail(p, "mesh: expected a string (a file name)");
    const std::string text = at(p).get<std::string>();
    constexpr std::string_view kDataPrefix = "data:";
    fs::path path;
    if (text.rfind(kDataPrefix, 0) == 0) {
      path = fs::path(text.substr(kDataPrefix.size()));
      if (path.empty() || path.is_absolute()) doc_.fail(p, "mesh: \"data:\" needs a file name relative to the data folder");
      path = dataDir_ / path;
    } else {
      path = fs::path(text);
      if (path.empty()) doc_.fail(p, "mesh: empty file name");
      if (path.is_relative()) path = presetDir_ / path;
    }
    return fs::absolute(path).lexically_normal();
  }

  sss::Material readMaterial(const Ptr& p) const {
    const json& v = at(p);
    if (v.is_string()) {
      const std::string name = v.get<std::string>();
      if (auto m = materials_.find(name)) return *m;
      std::vector<std::string> names;
      for (const sss::Material& m : materials_.materials()) names.push_back(m.name);
      doc_.fail(p, "unknown material " + quote(name) + didYouMean(name, names));
    }
    if (!v.is_object()) doc_.fail(p, "material: expected a name from materials.csv or an object of coefficients");
    if (has(p, "subsurface_color")) return readAppearance(p);
    checkKeys(p, kMaterialKeys, "material coefficients");
    sss::Material m;
    m.name = "custom";
    const bool derived = has(p, "from");
    if (derived) {
      // A measured material, optionally with coefficients replaced and σ_s, σ_a scaled (the
      // radiosity-maps paper's candle: glycerine soap scaled to approximate candle wax, §4).
      const Ptr from = p / "from";
      if (!at(from).is_string()) doc_.fail(from, "from: expected a material name from materials.csv");
      m = readMaterial(from);
    } else {
      if (has(p, "scale")) doc_.failAtKey(p / "scale", "\"scale\" applies to a material given \"from\" a measured one");
      m.sigma_s = vec3(require(p, "sigma_s"), "sigma_s", kCoefficient);
      m.sigma_a = vec3(require(p, "sigma_a"), "sigma_a", kCoefficient);
      m.g = glm::vec3(0.0f);
      m.eta = kDefaultEta;
    }
    if (derived && has(p, "sigma_s")) m.sigma_s = vec3(p / "sigma_s", "sigma_s", kCoefficient);
    if (derived && has(p, "sigma_a")) m.sigma_a = vec3(p / "sigma_a", "sigma_a", kCoefficient);
    if (has(p, "g")) {
      const Ptr g = p / "g";
      m.g = at(g).is_number() ? glm::vec3(number(g, "g", kAnisotropy)) : vec3(g, "g", kAnisotropy);
    }
    if (has(p, "eta")) m.eta = number(p / "eta", "eta", kEta);
    if (derived) {
      const float scale = optNumber(p, "scale", kMaterialScale).value_or(1.0f);
      m.sigma_s *= scale;
      m.sigma_a *= scale;
      std::ostringstream name;
      name << m.name << " x" << scale;
      if (scale != 1.0f) m.name = name.str();
    }
    try {
      sss::validateMaterial(m);
    } catch (const std::invalid_argument& e) {
      doc_.fail(p, std::string("invalid material: ") + e.what());
    }
    return m;
  }

  /// "material": {"subsurface_color": [r, g, b], "subsurface_radius_mm": s, "subsurface_radius_scale":
  /// [r, g, b], "eta": e, "g": g}: OpenPBR's terms, turned into σ_a and σ_s by inverting the standard
  /// dipole's total diffuse reflectance (sss/bssrdf/subsurface_appearance.h).
  sss::Material readAppearance(const Ptr& p) const {
    checkKeys(p, kAppearanceKeys, "a material in OpenPBR's terms");
    sss::SubsurfaceAppearance a;
    a.color = vec3(require(p, "subsurface_color"), "subsurface_color", kSubsurfaceColor);
    a.radiusMm = number(require(p, "subsurface_radius_mm"), "subsurface_radius_mm", kSubsurfaceRadiusMm);
    if (has(p, "subsurface_radius_scale"))
      a.radiusScale = vec3(p / "subsurface_radius_scale", "subsurface_radius_scale", kSubsurfaceRadiusScale);
    a.eta = has(p, "eta") ? number(p / "eta", "eta", kEta) : kDefaultEta;
    if (has(p, "g")) {
      const Ptr g = p / "g";
      a.g = at(g).is_number() ? glm::vec3(number(g, "g", kAnisotropy)) : vec3(g, "g", kAnisotropy);
    }
    try {
      return sss::materialFromAppearance(a);
    } catch (const std::invalid_argument& e) {
      doc_.fail(p, std::string("invalid material: ") + e.what());
    }
  }

  /// "volume": {"material": …, "period": 0.01, "axis": [0, 1, 0], "fraction": 0.5, "turbulence": 0,
  /// "seed": 0}: a second material in layers (veins with turbulence) inside a translucent object.
  sss::MaterialVolume readVolume(const Ptr& p) const {
    checkKeys(p, kVolumeKeys, "a volume");
    sss::MaterialVolume v;
    v.material = readMaterial(require(p, "material"));
    v.period = number(require(p, "period"), "period", kVolumePeriod);
    if (has(p, "axis")) v.axis = direction(p / "axis", "axis");
    v.fraction = optNumber(p, "fraction", kVolumeFraction).value_or(v.fraction);
    v.turbulence = optNumber(p, "turbulence", kVolumeTurbulence).value_or(v.turbulence);
    v.seed = optSeed(p, "seed").value_or(v.seed);
    return v;
  }

  /// "settings": registry keys, applied in document order; errors are re-located at the value.
  void applySettings(const Ptr& p, Config& config) const {
    if (!at(p).is_object()) doc_.fail(p, "settings: expected an object of parameter values");
    for (const std::string& key : doc_.keysInOrder(p)) {
      if (!registry_.find(key))
        doc_.failAtKey(p / key, "unknown parameter " + quote(key) + didYouMean(key, registry_.keys()));
      try {
        registry_.set(config, key, at(p / key));
      } catch (const InputError& e) {
        doc_.fail(p / key, e.what());
      }
    }
  }

  const JsonDocument& doc_;
  const Registry& registry_;
  const sss::MaterialTable& materials_;
  fs::path presetDir_;
  fs::path dataDir_;
};

}  // namespace

fs::path resolvePresetName(std::string_view nameOrPath, const fs::path& presetDir) {
  const std::string text(nameOrPath);
  // The preset's name goes into stats.json and bench.json, which must be UTF-8.
  if (!gpu::validUtf8(text)) throw InputError("preset " + quote(text) + ": the name is not valid UTF-8");
  const bool isPath = text.find('/') != std::string::npos ||
                      (text.size() >= 5 && text.compare(text.size() - 5, 5, ".json") == 0);
  if (isPath) {
    std::error_code ec;
    const fs::file_status status = fs::status(text, ec);
    if (!fs::exists(status)) throw InputError("no preset file " + quote(text));
    if (fs::is_directory(status)) throw InputError("preset " + quote(text) + " is a folder, not a JSON file");
    if (!fs::is_regular_file(status))
      throw InputError("preset " + quote(text) + " is not a regular file (a pipe, socket or device): give a JSON file");
    return fs::path(text);
  }
  const fs::path file = presetDir / (text + ".json");
  std::error_code ec;
  if (!text.empty() && fs::is_regular_file(file, ec)) return file;

  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(presetDir, ec))
    if (entry.path().extension() == ".json") names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end());
  std::string list;
  for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
  throw InputError("unknown preset " + quote(text) + didYouMean(text, names) + "; available: " +
                   (list.empty() ? "none in " + presetDir.string() : list));
}

Config loadPreset(const fs::path& file, const sss::MaterialTable& materials, const fs::path& dataDir) {
  const JsonDocument doc = JsonDocument::load(file);
  const Registry registry = parameterRegistry(materials);
  Config config = PresetReader(doc, registry, materials, file.parent_path(), dataDir).read();
  config.scene.sourcePath = fs::absolute(file).lexically_normal();
  return config;
}

Config parsePreset(std::string_view text, const std::string& fileName, const fs::path& presetDir,
                   const sss::MaterialTable& materials, const fs::path& dataDir) {
  const JsonDocument doc = JsonDocument::parse(text, fileName);
  const Registry registry = parameterRegistry(materials);
  Config config = PresetReader(doc, registry, materials, presetDir, dataDir).read();
  config.scene.sourcePath = fileName;
  return config;
}

}  // namespace tallow::app
