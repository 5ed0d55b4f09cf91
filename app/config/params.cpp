#include "app/config/params.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <memory>
#include <stdexcept>
#include <type_traits>

#include "app/config/input_error.h"

namespace tallow::app {

namespace {

using json = nlohmann::json;
using Param = Registry::Param;

// Bounds of scene coordinates (metres) and light magnitudes; generous, but finite so that every
// value fits a float and the panel can draw a slider.
constexpr double kMaxCoordinate = 1e4;
constexpr double kMaxRadiometric = 1e9;

glm::vec3 toVec3(const json& v) { return {v[0].get<float>(), v[1].get<float>(), v[2].get<float>()}; }
json toJson(const glm::vec3& v) { return json::array({floatToJson(v.x), floatToJson(v.y), floatToJson(v.z)}); }

sss::SceneObject& firstObject(Config& c) {
  if (c.scene.objects.empty()) throw InputError("the scene has no objects");
  return c.scene.objects.front();
}

sss::Light& firstLight(Config& c) {
  if (c.scene.lights.empty()) throw InputError("the scene has no lights");
  return c.scene.lights.front();
}

Param declare(std::string key, std::string type, std::string units, std::string help, double min = 0,
              double max = 0) {
  Param p;
  p.key = std::move(key);
  p.type = std::move(type);
  p.units = std::move(units);
  p.help = std::move(help);
  p.min = min;
  p.max = max;
  return p;
}

/// Binds a parameter to one plain field. `field` is a generic lambda `(auto& config) -> auto&`
/// returning the field, so it serves the getter (const Config) and the setter alike.
template <typename T, typename Field>
Param bind(Param p, Field field) {
  p.getter = [field](const Config& c) {
    if constexpr (std::is_same_v<T, float>) return floatToJson(field(c));
    else return json(field(c));
  };
  p.setter = [field](Config& c, const json& v) { field(c) = v.get<T>(); };
  return p;
}

/// Binds an int parameter that also takes "auto" (RenderSettings' kAuto, 0, in the field): the
/// renderer chooses the value from the scene (sss.map_size, sss.maps, sss.light_map_size).
/// `offValue`: what the panel sets when its auto checkbox is cleared (the paper's value).
template <typename Field>
Param bindIntOrAuto(Param p, double offValue, Field field) {
  p.acceptsAuto = true;
  p.autoOffValue = offValue;
  p.getter = [field](const Config& c) { return field(c) == sss::kAuto ? json("auto") : json(field(c)); };
  p.setter = [field](Config& c, const json& v) { field(c) = v.is_string() ? sss::kAuto : v.get<int>(); };
  return p;
}

/// An int whose frame cost grows as value^power in the passes it feeds (the panel's hint while it is
/// dragged: issue 40's sss.samples nudged from 8 to 147 made a frame 18 times longer, unannounced).
Param withCost(Param p, int power) {
  p.costPower = power;
  return p;
}

Param withDefault(Param p, json value) {
  p.defaultValue = std::move(value);
  return p;
}

/// Parameters the view panel needs to edit the scene beyond the preset's values (issue 9): the
/// first object's material coefficients, the first light's type, an orthographic camera's height.
void addSceneEditParams(Registry& r) {
  // The first object's coefficients one by one (mm⁻¹, per band); checked by sss::validateMaterial
  // as a preset's are. A change keeps the measured material's name with a mark, "Marble
  // (modified)", so the panel still says what it started from; setting the value it has keeps the
  // name (a saved preset re-applies every value).
  const auto material = [&r](std::string key, std::string type, std::string units, std::string help, double min,
                             double max, auto field) {
    Param p = declare(std::move(key), std::move(type), std::move(units), std::move(help), min, max);
    p.getter = [field](const Config& c) -> json {
      if (c.scene.objects.empty() || !c.scene.objects.front().translucent) return json(nullptr);
      const auto& v = field(c.scene.objects.front().material);
      if constexpr (std::is_same_v<std::decay_t<decltype(v)>, float>) return floatToJson(v);
      else return toJson(v);
    };
    p.setter = [field](Config& c, const json& v) {
      sss::SceneObject& object = firstObject(c);
      if (!object.translucent) throw InputError("the first object is opaque (give it a material first)");
      sss::Material m = object.material;
      auto& slot = field(m);
      using T = std::decay_t<decltype(slot)>;
      T value{};
      if constexpr (std::is_same_v<T, float>) value = v.get<float>();
      else value = toVec3(v);
      if (value == slot) return;
      slot = value;
      try {
        sss::validateMaterial(m);
      } catch (const std::invalid_argument& e) {
        throw InputError(e.what());
      }
      m.name = modifiedMaterialName(m.name);
      object.material = m;
    };
    r.add(std::move(p));
  };
  constexpr double kMaxCoefficient = 1e6;  // mm⁻¹, as a preset's coefficients
  material("material.sigma_a", "vec3", "mm⁻¹", "Absorption coefficient σ_a of the first object, per band.", 0,
           kMaxCoefficient, [](auto& m) -> auto& { return m.sigma_a; });
  material("material.sigma_s", "vec3", "mm⁻¹", "Scattering coefficient σ_s of the first object, per band.", 0,
           kMaxCoefficient, [](auto& m) -> auto& { return m.sigma_s; });
  material("material.g", "vec3", "", "Henyey-Greenstein mean cosine g of the first object, per band; |g| < 1.", -1, 1,
           [](auto& m) -> auto& { return m.g; });
  material("material.eta", "float", "", "Relative index of refraction η (inside / outside) of the first object.", 0,
           10, [](auto& m) -> auto& { return m.eta; });

  {
    Param p = declare("light.type", "enum", "",
                      "Kind of the first light. A directional light becomes a point light at its direction from the "
                      "camera target, as far as the camera is, with the intensity that keeps the irradiance at the "
                      "target (I = E d²); a point light becomes a directional light toward where it stood, E = I / d².");
    p.choices = {"directional", "point"};
    p.getter = [](const Config& c) {
      if (c.scene.lights.empty()) return json(nullptr);
      return json(c.scene.lights.front().kind == sss::LightKind::Point ? "point" : "directional");
    };
    p.setter = [](Config& c, const json& v) {
      sss::Light& light = firstLight(c);
      const sss::LightKind kind = v.get<std::string>() == "point" ? sss::LightKind::Point : sss::LightKind::Directional;
      if (kind == light.kind) return;
      const glm::vec3 target = c.scene.camera.target;
      const float d = std::max(glm::length(c.scene.camera.position - target), 1e-3f);
      if (kind == sss::LightKind::Point) {
        light.position = target + d * light.direction;
        light.intensity *= d * d;
      } else {
        if (light.follow >= 0)
          throw InputError("the first light follows a candle's flame; pin it with light.position first");
        const glm::vec3 toLight = light.position - target;
        const float r = glm::length(toLight);
        if (!(r > 0.0f)) throw InputError("the point light stands at the camera target: no direction to keep");
        light.direction = toLight / r;
        light.intensity /= r * r;
      }
      light.kind = kind;
      light.follow = -1;
    };
    r.add(std::move(p));
  }
  {
    Param p = declare("camera.height", "float", "m", "Height of the view of an orthographic camera.", 1e-5,
                      kMaxCoordinate);
    p.getter = [](const Config& c) {
      return c.scene.camera.orthographic ? floatToJson(c.scene.camera.orthoHeight) : json(nullptr);
    };
    p.setter = [](Config& c, const json& v) {
      if (!c.scene.camera.orthographic) throw InputError("the camera is perspective (it has a field of view, not a height)");
      c.scene.camera.orthoHeight = v.get<float>();
    };
    r.add(std::move(p));
  }
}

}  // namespace

std::string modifiedMaterialName(const std::string& name) {
  if (name.empty() || name == "custom") return "custom";
  if (name.size() >= kModifiedSuffix.size() &&
      name.compare(name.size() - kModifiedSuffix.size(), kModifiedSuffix.size(), kModifiedSuffix) == 0)
    return name;
  return name + std::string(kModifiedSuffix);
}

Registry parameterRegistry(const sss::MaterialTable& materials) {
  Registry r;

  // --- Output and rasterisation ---------------------------------------------------------------
  r.add(bind<int>(withDefault(declare("render.width", "int", "px", "Width of the rendered image.", 1, 16384), 960),
                  [](auto& c) -> auto& { return c.render.width; }));
  r.add(bind<int>(withDefault(declare("render.height", "int", "px", "Height of the rendered image.", 1, 16384), 540),
                  [](auto& c) -> auto& { return c.render.height; }));
  r.add(bind<bool>(withDefault(declare("render.shadows", "bool", "", "Shadow maps for the lights that cast shadows."),
                               true),
                   [](auto& c) -> auto& { return c.render.shadows; }));
  r.add(bind<int>(withDefault(declare("render.shadow_map_size", "int", "texels",
                                      "Edge length of each light's shadow map.", 16, 16384),
                              2048),
                  [](auto& c) -> auto& { return c.render.shadowMapSize; }));
  r.add(bind<float>(withDefault(declare("render.shadow_bias", "float", "texels",
                                        "Extra offset of the shadow lookup along the surface normal, in shadow-map "
                                        "texels, on top of the PCF footprint "
                                        "(pcf_radius + 1 texels, which alone rules out acne on flat surfaces).", 0, 16),
                                1.5),
                    [](auto& c) -> auto& { return c.render.shadowBias; }));
  r.add(bind<int>(withDefault(declare("render.pcf_radius", "int", "texels",
                                      "Percentage-closer filtering radius; 0 reads the shadow map once.", 0, 4),
                              1),
                  [](auto& c) -> auto& { return c.render.pcfRadius; }));
  {
    Param p = withDefault(declare("render.tonemap", "enum", "",
                                  "Tone-mapping operator of PNG and window output: clamp (clip to [0, 1]), reinhard "
                                  "(c / (1 + c) per channel), aces (Narkowicz's fit of the ACES filmic curve, per "
                                  "channel) or hue-preserving (a sigmoid of log luminance that keeps each colour's "
                                  "hue and takes very bright colours to white instead of clipping a channel; "
                                  "shaders/common/tonemap.glsl)."),
                          "aces");
    p.choices = {"clamp", "reinhard", "aces", "hue-preserving"};
    p.getter = [](const Config& c) { return json(std::string(gpu::toneMapName(c.render.toneMap.op))); };
    p.setter = [](Config& c, const json& v) { c.render.toneMap.op = gpu::parseToneMap(v.get<std::string>()); };
    r.add(std::move(p));
  }
  r.add(bind<float>(withDefault(declare("render.exposure_ev", "float", "stops",
                                        "Exposure before tone mapping: radiance is scaled by 2^ev.", -20, 20),
                                0.0),
                    [](auto& c) -> auto& { return c.render.toneMap.exposureEv; }));

  r.add(bind<int>(withDefault(declare("render.aa", "int", "samples",
                                      "Anti-aliasing of stills: while the picture does not change (paused, capture "
                                      "--accumulate, a still scene) each frame is drawn at the next of this many "
                                      "sub-pixel positions (the centre, then Halton points) and the frames are "
                                      "averaged, edges included; any change restarts at the pixel centres. 1: off.",
                                      1, 256),
                              16),
                  [](auto& c) -> auto& { return c.render.aaSamples; }));
  r.add(bind<float>(withDefault(declare("render.bloom", "float", "",
                                        "Glare around bright light (a candle's flame): this share of the picture's "
                                        "light spread by a point-spread function falling off as 1/r² from 2 to 64 "
                                        "pixels, before tone mapping, flux kept; in the window, PNGs and videos, not "
                                        "in the EXR's radiance. 0: off.",
                                        0, 1),
                                0.0),
                    [](auto& c) -> auto& { return c.render.bloom; }));
  r.add(bind<float>(withDefault(declare("render.local_exposure", "float", "",
                                        "Local adaptation, as the eye sees a dim table beside a bright flame: each "
                                        "region of the picture (its edge-aware mean log luminance, a bilateral "
                                        "grid) darker than mid grey is brought this share of its distance nearer "
                                        "to it; brighter regions and the detail within a region unchanged; in the "
                                        "window, PNGs and videos, not in the EXR's radiance. 0: off.",
                                        0, 1),
                                0.0),
                    [](auto& c) -> auto& { return c.render.localExposure; }));
  r.add(bind<bool>(withDefault(declare("render.specular", "bool", "",
                                       "Fresnel-weighted specular reflection on translucent objects: the environment "
                                       "map in the mirror direction, or the uniform ambient sky without one."),
                               true),
                   [](auto& c) -> auto& { return c.render.specular; }));
  r.add(bind<bool>(withDefault(declare("render.flame", "bool", "",
                                       "Draw the flame of a burning candle (a light that follows a candle field): "
                                       "emissive, after the surface pass, out of the light G-buffers and maps; its "
                                       "light is the point light's. tallow bench turns it off: the CPU reference "
                                       "has no flame to compare it with."),
                               true),
                   [](auto& c) -> auto& { return c.render.flame; }));
  r.add(bind<float>(withDefault(declare("flame.exposure_ev", "float", "stops",
                                        "The drawn flame's own exposure: its radiance × 2^ev before the picture's tone "
                                        "map. A flame is a hundred times brighter than the wax it lights, so one "
                                        "exposure shows it white where the eye, adapting locally, sees it yellow and "
                                        "orange; the light it casts is its full flux whatever this is.",
                                        -20, 20),
                                -2.5f),
                    [](auto& c) -> auto& { return c.render.flameExposureEv; }));
  {
    // Part of the scene (a preset's "settings" set it; no default of the registry's own): it moves
    // and colours the lights that follow a candle's flame.
    Param p = declare("flame.flicker", "float", "",
                      "How much a candle's flame flickers, deterministic in t: 1 is gentle (about ±2.5% of brightness "
                      "and ±3% of height, half a millimetre of sway at its centre), 0 a steady flame. The point light "
                      "that follows the flame flickers with it.",
                      0, 4);
    p.getter = [](const Config& c) { return floatToJson(c.scene.flameFlicker); };
    p.setter = [](Config& c, const json& v) { c.scene.flameFlicker = v.get<float>(); };
    r.add(std::move(p));
  }
  r.add(bind<int>(withCost(withDefault(declare("field.res", "int", "samples per axis",
                                      "Lattice resolution of field objects, isosurfaced on the GPU every frame.", 16,
                                      512),
                              64), 3),
                  [](auto& c) -> auto& { return c.render.fieldRes; }));
  {
    Param p = withDefault(
        declare("field.placement", "enum", "",
                "Where dual contouring puts each surface patch's vertex in its lattice cell: qef (the minimum of the "
                "squared distances to the tangent planes at the patch's edge crossings, regularised toward their "
                "mean as a probabilistic quadric, kept in the cell: sharp edges and corners stay sharp) or mass (the "
                "mean of the edge crossings, surface nets: rounds them off, edges about half a cell deep and corners up "
                "to a cell)."),
        std::string(geometry::vertexPlacementName(geometry::kDefaultPlacement)));
    p.choices = {"qef", "mass"};
    p.getter = [](const Config& c) { return json(std::string(geometry::vertexPlacementName(c.render.fieldPlacement))); };
    p.setter = [](Config& c, const json& v) {
      c.render.fieldPlacement = geometry::parseVertexPlacement(v.get<std::string>());
    };
    r.add(std::move(p));
  }

  {
    Param p = withDefault(
        declare("field.extraction", "enum", "",
                "Which shader stages run dual contouring's vertex and triangle passes: compute (compute shaders "
                "write the records into buffers with atomics, drawn indirectly: keeps the work off the raster units, "
                "which some GPUs have few of) or geometry (geometry shaders captured by transform feedback, the "
                "radiosity-maps paper's path). Both make the same vertices and triangles; the default measured "
                "faster (docs/RESULTS.md, `tallow probe extraction`)."),
        std::string(geometry::extractionPathName(geometry::kDefaultExtraction)));
    p.choices = {"compute", "geometry"};
    p.getter = [](const Config& c) { return json(std::string(geometry::extractionPathName(c.render.fieldExtraction))); };
    p.setter = [](Config& c, const json& v) {
      c.render.fieldExtraction = geometry::parseExtractionPath(v.get<std::string>());
    };
    r.add(std::move(p));
  }

  {
    Param p = withDefault(
        declare("field.evaluate", "enum", "",
                "Where an animated field is evaluated each frame: gpu (the blob, the candle and melting meshes by a "
                "compute shader from t, normals from the analytic gradient; no upload) or cpu (every field sampled on "
                "the CPU in double and uploaded, normals from the lattice: the path before the GPU fields, kept to "
                "measure against). A mesh field that does not melt is sampled on the CPU once either way."),
        "gpu");
    p.choices = {"gpu", "cpu"};
    p.getter = [](const Config& c) { return json(c.render.fieldOnGpu ? "gpu" : "cpu"); };
    p.setter = [](Config& c, const json& v) { c.render.fieldOnGpu = v.get<std::string>() == "gpu"; };
    r.add(std::move(p));
  }

  // --- Subsurface scattering (issue 5; Dal Corso et al. 2017, "the paper" below) -----------------
  {
    Param p = withDefault(declare("method", "enum", "",
                                  "How translucent objects are shaded: radiosity-maps (the paper's scattered radiosity "
                                  "maps), no-cache (the same gather per camera pixel against the light G-buffers, "
                                  "as translucent shadow maps; no maps, a new estimate every frame), image-space "
                                  "(local subsurface scattering integrated in the camera image by importance "
                                  "sampling of the standard dipole, Mertens et al. 2003; parameters image_space.*), "
                                  "sslpv (subsurface light propagation volumes, Borlum et al. 2011: sslpv.*, "
                                  "docs/sslpv.md), burley (what production engines ship: Christensen and Burley's "
                                  "normalised diffusion profile sampled in screen space, with transmission through "
                                  "thin parts from the shadow maps; burley.*, docs/burley.md) or albedo (Lambertian "
                                  "with the object's albedo, no subsurface transport)."),
                          "radiosity-maps");
    p.choices = {"radiosity-maps", "no-cache", "sslpv", "image-space", "burley", "albedo"};
    p.getter = [](const Config& c) {
      switch (c.render.sss.method) {
        case sss::SssMethod::RadiosityMaps: return json("radiosity-maps");
        case sss::SssMethod::NoCache: return json("no-cache");
        case sss::SssMethod::ImageSpace: return json("image-space");
        case sss::SssMethod::Sslpv: return json("sslpv");
        case sss::SssMethod::Burley: return json("burley");
        case sss::SssMethod::Albedo: break;
      }
      return json("albedo");
    };
    p.setter = [](Config& c, const json& v) {
      const std::string m = v.get<std::string>();
      c.render.sss.method = m == "albedo"        ? sss::SssMethod::Albedo
                            : m == "no-cache"    ? sss::SssMethod::NoCache
                            : m == "image-space" ? sss::SssMethod::ImageSpace
                            : m == "sslpv"       ? sss::SssMethod::Sslpv
                            : m == "burley"      ? sss::SssMethod::Burley
                                                 : sss::SssMethod::RadiosityMaps;
    };
    r.add(std::move(p));
  }
  {
    Param p = withDefault(declare("sss.model", "enum", "",
                                  "BSSRDF evaluated in the radiosity maps: directional (Frisvad et al. 2014), standard "
                                  "(Jensen et al. 2001) or pbd (photon beam diffusion, Habel et al. 2013)."),
                          "directional");
    p.choices = {"directional", "standard", "pbd"};
    p.getter = [](const Config& c) { return json(std::string(sss::bssrdfModelName(c.render.sss.model))); };
    p.setter = [](Config& c, const json& v) { c.render.sss.model = sss::parseBssrdfModel(v.get<std::string>()); };
    r.add(std::move(p));
  }
  r.add(bindIntOrAuto(withCost(withDefault(declare("sss.maps", "int", "maps",
                                      "K: scattered radiosity maps, from Halton directions on the bounding sphere (the "
                                      "paper uses 16 for simple shapes, 28 for the candle, 31 for the dragon); auto: "
                                      "the fewest of them that see all but 0.1% of the translucent pixels and VPLs "
                                      "that more maps would see, measured every frame (at most 32, 16 at first; "
                                      "docs/radiosity-maps.md). The GPU's array-layer and memory limits are checked "
                                      "when the renderer starts.", 1, 256),
                              "auto"), 1),
                      16, [](auto& c) -> auto& { return c.render.sss.maps; }));
  r.add(bind<int>(withCost(withDefault(declare("sss.samples", "int", "samples",
                                      "N: samples per map texel, frame and colour band of the estimator (Eq. 9).", 1,
                                      4096),
                              8), 1),
                  [](auto& c) -> auto& { return c.render.sss.samples; }));
  r.add(bindIntOrAuto(withCost(withDefault(declare("sss.map_size", "int", "texels",
                                          "Edge of each scattered radiosity map; auto: a texel no wider than half a "
                                          "pixel of the objects on screen (asking at most 512) nor than the shortest "
                                          "1/sigma_tr, as a power of two in [128, 2048], chosen when the maps restart "
                                          "(docs/radiosity-maps.md).",
                                          16, 8192),
                                  "auto"), 2),
                      512, [](auto& c) -> auto& { return c.render.sss.mapSize; }));
  r.add(bindIntOrAuto(withCost(withDefault(declare("sss.light_map_size", "int", "texels",
                                          "Edge of each light's G-buffer (a cube face for point lights); auto: a "
                                          "texel of a quarter of the shortest 1/sigma_tr over the objects' bounding "
                                          "sphere, as a power of two in [512, 4096] (point lights: 1024).",
                                          16, 8192),
                                  "auto"), 2),
                      512, [](auto& c) -> auto& { return c.render.sss.lightMapSize; }));
  r.add(bind<float>(withDefault(declare("sss.bias", "float", "× radius",
                                        "ε_bias: depth offset of the radiosity maps' visibility test (Algorithm 1), in "
                                        "units of the translucent objects' bounding radius.", 0, 1),
                                0.01),
                    [](auto& c) -> auto& { return c.render.sss.bias; }));
  r.add(bind<float>(withDefault(declare("sss.comb", "float", "× radius",
                                        "ε_comb: offset of the map lookup along −n_o, tangent to the map direction "
                                        "(Algorithm 1), in units of the translucent objects' bounding radius.", 0, 1),
                                0.005),
                    [](auto& c) -> auto& { return c.render.sss.comb; }));
  r.add(bind<float>(withDefault(declare("sss.view_weight", "float", "",
                                        "p: Algorithm 1 weights each map that sees x_o by cos^p θ, θ between n_o and "
                                        "the map's direction, so that maps seeing x_o face-on (sharp texels) decide; 0 "
                                        "is the paper's equal weighting (docs/radiosity-maps.md, RESULTS.md).", 0, 8),
                                2.0),
                    [](auto& c) -> auto& { return c.render.sss.viewWeight; }));
  r.add(bind<int>(withDefault(declare("sss.frames", "int", "frames",
                                      "Frames accumulated while light and geometry stay still; then the maps are "
                                      "converged and only the camera pass runs.", 1, 1 << 20),
                              64),
                  [](auto& c) -> auto& { return c.render.sss.frames; }));
  r.add(bind<int>(withDefault(declare("sss.history", "int", "frames",
                                      "When the geometry deforms or a light moves, the maps are not restarted: each "
                                      "map texel whose surface point (within sss.history_move) and normal (within 25 "
                                      "degrees) still hold keeps at most this many frames of its estimate, the others "
                                      "start again, and what is kept is rescaled to follow a moving light "
                                      "(sss.history_rescale); 0 restarts the maps on every change, as the paper "
                                      "does (docs/RESULTS.md compares the two). When the motion stops, the kept frames fade out over "
                                      "sss.frames frames, so the still ends where a restart's would.",
                                      0, 1 << 20),
                              8),
                  [](auto& c) -> auto& { return c.render.sss.history; }));
  r.add(bind<float>(withDefault(declare("sss.history_move", "float", "× 1/σ_tr",
                                        "How far a map texel's surface point may move from one frame to the next and "
                                        "keep its history (sss.history), in units of the shortest diffusion length "
                                        "1/sigma_tr of the translucent materials: B changes on that scale.",
                                        0, 100),
                                0.5),
                    [](auto& c) -> auto& { return c.render.sss.historyMove; }));
  r.add(bind<float>(withDefault(declare("sss.history_rescale", "float", "× 1/σ_tr",
                                        "With sss.history: the footprint, in units of the shortest diffusion length, "
                                        "over which each kept history is rescaled band by band to this frame's "
                                        "estimate (the ratio of their means on a coarse mip level), so that it follows "
                                        "a light that moves while the surface holds (the candle's sinking flame); a "
                                        "ratio beyond 4 or under 1/4 starts the texel again. 0: the history is kept "
                                        "as it was.",
                                        0, 1000),
                                1.0),
                    [](auto& c) -> auto& { return c.render.sss.historyRescale; }));
  r.add(bind<bool>(withDefault(declare("sss.light_map_auto", "bool", "",
                                       "Raise the light G-buffer size above sss.light_map_size (to a power of two, at "
                                       "most the GPU's texture limit and 8192) until a texel is no larger than the "
                                       "shortest mean free path 1/σ_tr, against pearling (the paper's §5)."),
                               false),
                   [](auto& c) -> auto& { return c.render.sss.lightMapAuto; }));
  r.add(bind<bool>(withDefault(declare("sss.projected_area", "bool", "",
                                       "The estimator's samples lie on a plane (a directional light's view plane, x_o's "
                                       "tangent plane for a point light), not on the surface; on: weight each by the "
                                       "surface's area per plane area (Eq. 7 exactly), off: the paper's Eq. 9 as "
                                       "printed, which loses a factor cos θ_ℓ at grazing light and brightens concave "
                                       "walls near a point light."),
                               true),
                   [](auto& c) -> auto& { return c.render.sss.projectedArea; }));
  r.add(bind<bool>(withDefault(declare("sss.texel_plane", "bool", "",
                                       "Where a sample meets the light G-buffer: on: x_i where the look-up line "
                                       "meets the texel's tangent plane; off: the texel's depth along the line, "
                                       "which leaves x_i up to half a texel x tan θ_ℓ off a tilted surface and loses "
                                       "light at grazing incidence."),
                               true),
                   [](auto& c) -> auto& { return c.render.sss.texelPlane; }));
  {
    Param p = withDefault(declare("sss.gather", "enum", "",
                                  "How step 2 runs the estimator: fragment (the paper: the maps' texels as fragments "
                                  "of a layered pass) or compute (a compute pass over the maps' G-buffer; same "
                                  "inputs and seeds, same result; on llvmpipe about 10x faster, see docs/RESULTS.md)."),
                          "compute");
    p.choices = {"fragment", "compute"};
    p.getter = [](const Config& c) { return json(c.render.sss.computeGather ? "compute" : "fragment"); };
    p.setter = [](Config& c, const json& v) { c.render.sss.computeGather = v.get<std::string>() == "compute"; };
    r.add(std::move(p));
  }
  r.add(bind<bool>(withDefault(declare("sss.stereographic", "bool", "",
                                       "Stereographic correction (Eqs. 13–14) of point-light G-buffer lookups; off: "
                                       "planar sampling (the paper's Fig. 4a)."),
                               true),
                   [](auto& c) -> auto& { return c.render.sss.stereographic; }));
  r.add(bind<float>(withDefault(declare("sss.point_share", "float", "",
                                        "Point lights: the share of samples drawn uniformly in direction about the "
                                        "light (mapped stereographically onto x_o's tangent plane) instead of Eq. 12's "
                                        "exponential, weighted by the mixture's density. It reaches wax lit from "
                                        "centimetres away, which Eq. 12 almost never samples and cuts off at "
                                        "16.6/sigma_tr. Directional lights use the same share where x_o lies more than "
                                        "1/sigma_tr behind the lit surface (a thick, backlit object), with a scale of "
                                        "sqrt(depth/sigma_tr); 0: Eq. 12 alone (the paper).", 0.0, 0.95),
                                0.25),
                    [](auto& c) -> auto& { return c.render.sss.pointShare; }));

  // --- Subsurface light propagation volumes (issue 8; Borlum et al. 2011, docs/sslpv.md) ------------
  r.add(bind<int>(withDefault(declare("sslpv.grid", "int", "cells per axis",
                                      "N: the LPV grid of N^3 cubic cells around the translucent objects (the paper "
                                      "uses 32, and 64 for its Fig. 9b). Memory and the GPU's texture limits are "
                                      "checked when the renderer starts.", 8, 512),
                              32),
                  [](auto& c) -> auto& { return c.render.sslpv.grid; }));
  r.add(bind<int>(withDefault(declare("sslpv.steps", "int", "steps",
                                      "Propagation steps; light moves one cell per step (the paper uses 8 to 64, "
                                      "mostly 32).", 1, 4096),
                              32),
                  [](auto& c) -> auto& { return c.render.sslpv.steps; }));
  r.add(bind<int>(withDefault(declare("sslpv.skip", "int", "steps",
                                      "The first propagation steps left out of the accumulation grid (the paper "
                                      "skips 2 against flicker); must be less than sslpv.steps.", 0, 4095),
                              2),
                  [](auto& c) -> auto& { return c.render.sslpv.skip; }));
  r.add(bind<int>(withDefault(declare("sslpv.inject_size", "int", "texels",
                                      "Edge of the light G-buffers (a cube face for point lights) whose texels are "
                                      "injected (the paper injects 256^2).", 16, 8192),
                              256),
                  [](auto& c) -> auto& { return c.render.sslpv.injectSize; }));
  {
    Param p = withDefault(declare("sslpv.exitance", "enum", "",
                                  "Which flux of a surface cell's point light the area light of Eq. 7 carries out: "
                                  "hemisphere (the paper's Eq. 5: all of the half space about the normal) or face "
                                  "(the cap of 2pi/3 sr that one face of the cell subtends: the flux the propagation "
                                  "passes across the surface per step; docs/sslpv.md)."),
                          "hemisphere");
    p.choices = {"hemisphere", "face"};
    p.getter = [](const Config& c) {
      return json(c.render.sslpv.exitance == sss::SslpvExitance::Face ? "face" : "hemisphere");
    };
    p.setter = [](Config& c, const json& v) {
      c.render.sslpv.exitance = v.get<std::string>() == "face" ? sss::SslpvExitance::Face : sss::SslpvExitance::Hemisphere;
    };
    r.add(std::move(p));
  }

  // --- Emergent light by virtual point lights (issue 7; the paper's §3.4, docs/vpl.md) -----------
  r.add(bind<int>(withCost(withDefault(declare("vpl.count", "int", "VPLs",
                                      "N_vpl: virtual point lights on the translucent objects' outermost surface that "
                                      "light the opaque receivers (Eqs. 15-16; the paper uses 50-200); 0: none. Needs "
                                      "method radiosity-maps.", 0, sss::kMaxVpls),
                              0), 1),
                  [](auto& c) -> auto& { return c.render.vpl.count; }));
  r.add(bind<int>(withDefault(declare("vpl.cube_size", "int", "texels",
                                      "Face of the cube map of the outermost surface from which the VPLs are read.", 8,
                                      4096),
                              128),
                  [](auto& c) -> auto& { return c.render.vpl.cubeSize; }));
  {
    Param p = withDefault(declare("vpl.placement", "enum", "",
                                  "Where VPLs stand: backlit (only surface facing away from every point light inside "
                                  "the translucent objects' box: the paper's visibility approximation for a "
                                  "surrounded source), all (the whole outermost surface), or auto (backlit when such "
                                  "a light exists, else all)."),
                          "auto");
    p.choices = {"auto", "all", "backlit"};
    p.getter = [](const Config& c) {
      switch (c.render.vpl.placement) {
        case sss::VplPlacement::All: return json("all");
        case sss::VplPlacement::Backlit: return json("backlit");
        case sss::VplPlacement::Auto: break;
      }
      return json("auto");
    };
    p.setter = [](Config& c, const json& v) {
      const std::string m = v.get<std::string>();
      c.render.vpl.placement = m == "all"       ? sss::VplPlacement::All
                               : m == "backlit" ? sss::VplPlacement::Backlit
                                                : sss::VplPlacement::Auto;
    };
    r.add(std::move(p));
  }
  {
    Param p = withDefault(declare("vpl.area", "enum", "",
                                  "The area A_v each VPL stands for: solid-angle (4 pi d^2 / (N_vpl cos alpha) from the "
                                  "cube's centre: the density of the fixed directions on the surface, exact on "
                                  "average) or bounding-box (the paper's Eq. 16: the bounding box's area / N_vpl)."),
                          "solid-angle");
    p.choices = {"solid-angle", "bounding-box"};
    p.getter = [](const Config& c) {
      return json(c.render.vpl.area == sss::VplArea::SolidAngle ? "solid-angle" : "bounding-box");
    };
    p.setter = [](Config& c, const json& v) {
      c.render.vpl.area = v.get<std::string>() == "bounding-box" ? sss::VplArea::BoundingBox : sss::VplArea::SolidAngle;
    };
    r.add(std::move(p));
  }
  r.add(bind<bool>(withDefault(declare("vpl.stable", "bool", "",
                                       "The same VPL directions every frame (the paper's remedy for flicker); off: new "
                                       "directions every frame."),
                               true),
                   [](auto& c) -> auto& { return c.render.vpl.stable; }));
  r.add(bind<bool>(withDefault(declare("vpl.shadows", "bool", "",
                                       "Receivers' visibility of the VPLs (the paper has none): the VPLs are grouped "
                                       "by direction into vpl.shadow_clusters clusters, each with one cube shadow map "
                                       "from just outside its VPLs' mean position (docs/vpl.md)."),
                               false),
                   [](auto& c) -> auto& { return c.render.vpl.shadows; }));
  r.add(bind<int>(withDefault(declare("vpl.shadow_clusters", "int", "clusters",
                                      "C: cube shadow maps shared by the VPLs (with vpl.shadows).", 1,
                                      sss::kMaxVplShadowClusters),
                              64),
                  [](auto& c) -> auto& { return c.render.vpl.shadowClusters; }));
  r.add(bind<int>(withDefault(declare("vpl.shadow_size", "int", "texels",
                                      "Face of each VPL cluster's cube shadow map (with vpl.shadows).", 8, 2048),
                              64),
                  [](auto& c) -> auto& { return c.render.vpl.shadowSize; }));

  // --- Local subsurface scattering in image space (issue 8; Mertens et al. 2003, docs/image-space.md) --
  r.add(bind<int>(withDefault(declare("image_space.samples", "int", "samples",
                                      "N: samples per translucent pixel and frame on its tangent plane, shared by the "
                                      "colour bands (each sample serves all three).", 1, sss::kImageSpaceMaxSamples),
                              16),
                  [](auto& c) -> auto& { return c.render.imageSpace.samples; }));
  r.add(bind<float>(withDefault(declare("image_space.uniform_share", "float", "",
                                        "Share of the N samples drawn uniformly on the disc instead of by importance "
                                        "sampling of R_d (the paper's combined sampling, for points near a shadow "
                                        "border); combined by the balance heuristic.", 0, 1),
                                0.25),
                    [](auto& c) -> auto& { return c.render.imageSpace.uniformShare; }));
  r.add(bind<int>(withDefault(declare("image_space.tile", "int", "pixels",
                                      "T: interleaved sampling with T² sample sets, one per place in a T x T tile of "
                                      "pixels, combined by a geometry-aware T x T mean (1: one set, no mean).", 1,
                                      sss::kImageSpaceMaxTile),
                              4),
                  [](auto& c) -> auto& { return c.render.imageSpace.tile; }));
  r.add(bind<float>(withDefault(declare("image_space.radius", "float", "1/σ_tr",
                                        "Radius of the disc of x_o's tangent plane that is integrated (the paper's "
                                        "A'), in mean free paths of the colour band that scatters farthest.", 0.5, 64),
                                8.0),
                    [](auto& c) -> auto& { return c.render.imageSpace.radius; }));
  r.add(bind<int>(withDefault(declare("image_space.frames", "int", "frames",
                                      "Frames accumulated (new samples each) while camera, light and geometry stay "
                                      "still; then only the surface pass runs.", 1, 1 << 20),
                              32),
                  [](auto& c) -> auto& { return c.render.imageSpace.frames; }));
  r.add(bind<float>(withDefault(declare("image_space.depth_ratio", "float", "",
                                        "A sample is rejected as across a depth discontinuity when the surface it "
                                        "finds in the image lies farther than this times its distance r' from x_o "
                                        "(at least one pixel) from x_o's tangent plane point.", 0.01, 100),
                                1.0),
                    [](auto& c) -> auto& { return c.render.imageSpace.depthRatio; }));
  r.add(bind<bool>(withDefault(declare("image_space.jacobian", "bool", "",
                                       "Weight each sample by the surface area per tangent-plane area of the "
                                       "projection through the camera (the paper's Eq. 8; its GPU version leaves it "
                                       "out: off)."),
                               true),
                   [](auto& c) -> auto& { return c.render.imageSpace.jacobian; }));
  r.add(bind<bool>(withDefault(declare("image_space.renormalize", "bool", "",
                                       "Divide B by the sampled share of R_d that fell on x_o's visible surface, i.e. "
                                       "assume the unseen part is lit alike (the paper divides by the count of valid "
                                       "samples); off: the integral over the visible surface only."),
                               false),
                   [](auto& c) -> auto& { return c.render.imageSpace.renormalize; }));
  r.add(bind<int>(withDefault(declare("burley.samples", "int", "samples",
                                      "N: samples of the diffusion profile per translucent pixel and frame, on a disc "
                                      "facing the camera (the colour bands in turn), as engines sample it.",
                                      1, sss::kBurleyMaxSamples),
                              32),
                  [](auto& c) -> auto& { return c.render.burley.samples; }));
  r.add(bind<bool>(withDefault(declare("burley.transmission", "bool", "",
                                       "Light through thin parts: the thickness between a point and the first surface "
                                       "its light's shadow map sees, through the profile's transmittance (engines' "
                                       "\"thick object\" mode)."),
                               true),
                   [](auto& c) -> auto& { return c.render.burley.transmission; }));
  {
    Param p = withDefault(declare("burley.kernel", "enum", "",
                                  "How the profile is applied in screen space: disc (importance-sampled discs facing "
                                  "the camera, Unreal's Burley SSS; burley.samples per pixel) or separable (a "
                                  "horizontal then a vertical pass of burley.samples taps, Jimenez et al. 2015's "
                                  "structure); docs/burley.md has both against the reference."),
                          "disc");
    p.choices = {"disc", "separable"};
    p.getter = [](const Config& c) {
      return json(c.render.burley.kernel == sss::BurleyKernel::Separable ? "separable" : "disc");
    };
    p.setter = [](Config& c, const json& v) {
      c.render.burley.kernel = v.get<std::string>() == "separable" ? sss::BurleyKernel::Separable : sss::BurleyKernel::Disc;
    };
    r.add(std::move(p));
  }

  // --- Scene-bound: no default; the preset gives the value --------------------------------------
  {
    Param p = declare("scale", "float", "m", "Size of the first object (mesh: largest extent of its bounding box).",
                      1e-5, 1e3);
    p.getter = [](const Config& c) {
      return c.scene.objects.empty() ? json(nullptr) : floatToJson(c.scene.objects.front().transform.scale);
    };
    p.setter = [](Config& c, const json& v) { firstObject(c).transform.scale = v.get<float>(); };
    r.add(std::move(p));
  }
  {
    auto table = std::make_shared<const sss::MaterialTable>(materials);
    Param p = declare("material", "enum", "",
                      "Measured material of the first object (a row of materials.csv); makes it translucent.");
    for (const sss::Material& m : table->materials()) p.choices.push_back(m.name);
    p.getter = [](const Config& c) {
      if (c.scene.objects.empty() || !c.scene.objects.front().translucent) return json(nullptr);
      return json(c.scene.objects.front().material.name);
    };
    p.setter = [table](Config& c, const json& v) {
      sss::SceneObject& object = firstObject(c);
      object.material = table->find(v.get<std::string>()).value();  // a checked choice, so present
      object.translucent = true;
    };
    r.add(std::move(p));
  }
  {
    Param p = declare("light.intensity", "vec3", "W/m² or W/sr",
                      "First light: irradiance of a directional light or intensity of a point light, per band.", 0,
                      kMaxRadiometric);
    p.getter = [](const Config& c) {
      return c.scene.lights.empty() ? json(nullptr) : toJson(c.scene.lights.front().intensity);
    };
    p.setter = [](Config& c, const json& v) { firstLight(c).intensity = toVec3(v); };
    r.add(std::move(p));
  }
  {
    Param p = declare("light.direction", "vec3", "",
                      "First light, if directional: unit vector from the scene toward the light (normalised on set).",
                      -1, 1);
    p.getter = [](const Config& c) {
      if (c.scene.lights.empty() || c.scene.lights.front().kind != sss::LightKind::Directional) return json(nullptr);
      return toJson(c.scene.lights.front().direction);
    };
    p.setter = [](Config& c, const json& v) {
      sss::Light& light = firstLight(c);
      if (light.kind != sss::LightKind::Directional)
        throw InputError("the first light is a point light (it has light.position)");
      // In double: a tiny float vector's squared length would underflow to 0.
      const glm::dvec3 d(toVec3(v));
      if (d == glm::dvec3(0.0)) throw InputError("the direction must not be zero");
      light.direction = glm::vec3(d / glm::length(d));
    };
    r.add(std::move(p));
  }
  {
    Param p = declare("light.position", "vec3", "m",
                      "First light, if a point light: its position (a light that follows a candle's flame stays "
                      "here instead).",
                      -kMaxCoordinate, kMaxCoordinate);
    p.getter = [](const Config& c) {
      if (c.scene.lights.empty() || c.scene.lights.front().kind != sss::LightKind::Point) return json(nullptr);
      return toJson(c.scene.lights.front().position);
    };
    p.setter = [](Config& c, const json& v) {
      sss::Light& light = firstLight(c);
      if (light.kind != sss::LightKind::Point)
        throw InputError("the first light is directional (it has light.direction)");
      light.position = toVec3(v);
      light.follow = -1;
    };
    r.add(std::move(p));
  }
  {
    Param p = declare("camera.position", "vec3", "m", "Camera position.", -kMaxCoordinate, kMaxCoordinate);
    p.getter = [](const Config& c) { return toJson(c.scene.camera.position); };
    p.setter = [](Config& c, const json& v) { c.scene.camera.position = toVec3(v); };
    r.add(std::move(p));
  }
  {
    Param p = declare("camera.target", "vec3", "m", "Point the camera looks at.", -kMaxCoordinate, kMaxCoordinate);
    p.getter = [](const Config& c) { return toJson(c.scene.camera.target); };
    p.setter = [](Config& c, const json& v) { c.scene.camera.target = toVec3(v); };
    r.add(std::move(p));
  }
  {
    Param p = declare("camera.fov_deg", "float", "deg", "Vertical field of view of a perspective camera.", 1, 179);
    p.getter = [](const Config& c) {
      return c.scene.camera.orthographic ? json(nullptr) : floatToJson(c.scene.camera.fovYDeg);
    };
    p.setter = [](Config& c, const json& v) {
      if (c.scene.camera.orthographic) throw InputError("the camera is orthographic (it has a height, not a field of view)");
      c.scene.camera.fovYDeg = v.get<float>();
    };
    r.add(std::move(p));
  }
  {
    Param p = declare("ambient", "vec3", "W/(m²·sr)", "Uniform sky radiance lighting opaque surfaces, per band.", 0,
                      kMaxRadiometric);
    p.getter = [](const Config& c) { return toJson(c.scene.ambient); };
    p.setter = [](Config& c, const json& v) { c.scene.ambient = toVec3(v); };
    r.add(std::move(p));
  }
  addSceneEditParams(r);
  return r;
}

}  // namespace tallow::app
