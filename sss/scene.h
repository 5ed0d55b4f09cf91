#pragma once
// What a frame renders: objects, lights and camera, in metres. Filled from presets/*.json by
// app/config/preset.h; passes read it, never write it.
#include <glm/glm.hpp>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "sss/bssrdf/material.h"

namespace tallow::sss {

/// HollowCylinder (preset "hollow-cylinder"): a cup about +y standing on its bottom centre,
/// `size` = (inner radius, outer radius, height) in metres (× scale); the bottom is as thick as
/// the wall (outer − inner). See geometry::makeHollowCylinder.
enum class ShapeKind { Mesh, Sphere, Plane, Box, Field, HollowCylinder };

/// A procedural field isosurfaced every frame on the GPU (ShapeKind::Field, preset key "field").
enum class FieldKind { Blob, Candle, Mesh };

struct FieldDesc {
  FieldKind kind = FieldKind::Blob;
  double blobScale = 0.03;        ///< blob: metres per unscaled unit (BlobParams::scale)
  double candleDurationS = 20.0;  ///< candle: the animation's seconds (CandleParams::durationS)
  double candleTimeScale = 300.0;  ///< candle: real seconds per animation second (CandleParams::timeScale)
  int candleDrips = 10;            ///< candle: overflows over the animation (CandleParams::dripCount)
  std::uint32_t candleSeed = 1;    ///< candle: the overflows' times and places (CandleParams::seed)
  std::filesystem::path meshPath;  ///< mesh: the triangle mesh turned into a level set; absolute
  double meltDurationS = 0.0;      ///< mesh: seconds until fully melted (MeltParams); 0 = it does not melt
};

struct Transform {
  glm::vec3 position{0.0f};     ///< metres; where the shape's anchor goes (see SceneObject)
  glm::vec3 rotationDeg{0.0f};  ///< Euler angles, degrees, applied X then Y then Z
  /// Metres. Mesh: the largest extent of the mesh's bounding box after scaling. Sphere: radius.
  /// Box: edge length (multiplies `size`). Plane: multiplies `size`. Field: mesh fields only, the
  /// mesh's largest extent (blob and candle keep their own size).
  float scale = 1.0f;
};

/// A second material inside a translucent object, in layers across `axis` that turbulence warps
/// into veins (preset key "volume"; only SSLPV's heterogeneous medium reads it, the other methods
/// shade the object with its own material: shaders/peers/sslpv/volume.glsl, docs/sslpv.md).
struct MaterialVolume {
  Material material;                 ///< the second material
  glm::vec3 axis{0.0f, 1.0f, 0.0f};  ///< unit normal of the layers in the object's frame
  float period = 0.01f;              ///< metres from one layer to the next
  float fraction = 0.5f;             ///< share of each period in the second material, [0, 1]
  float turbulence = 0.0f;           ///< how far the layers wander (periods); 0: flat layers
  std::uint32_t seed = 0;            ///< of the turbulence's noise
};

struct SceneObject {
  std::string name;
  ShapeKind shape = ShapeKind::Mesh;
  std::filesystem::path meshPath;  ///< ShapeKind::Mesh only; absolute once loaded
  FieldDesc field;                 ///< ShapeKind::Field only
  glm::vec3 size{1.0f};            ///< Plane: (x extent, unused, z extent); Box: edge lengths
  Transform transform;
  /// Translucent objects carry a measured material; until a subsurface method exists for them
  /// they are drawn with `albedo` like opaque ones.
  bool translucent = false;
  Material material;
  std::optional<MaterialVolume> volume;  ///< translucent objects only: a heterogeneous interior
  /// A candle field's melt pool (preset key "pool_material"): the liquid part of its surface takes
  /// this material (sss/translucent_slots.h). The radiosity maps, no-cache, the VPLs and the CPU
  /// reference honour it; the peers shade the whole object with `material`.
  std::optional<Material> liquidMaterial;
  /// Where the liquid is at the frame's time, in object units (shaders/materials/liquid_surface.glsl's
  /// region: pool surface y, radius, meniscus height, tolerance); set by sceneAtTime, radius 0: none.
  glm::vec4 liquidRegion{0.0f};
  glm::vec3 albedo{0.8f};  ///< Lambertian reflectance of the opaque path, in [0, 1]
};

enum class LightKind { Directional, Point };

struct Light {
  LightKind kind = LightKind::Directional;
  glm::vec3 direction{0.0f, 1.0f, 0.0f};  ///< directional: unit vector from the scene toward the light
  glm::vec3 position{0.0f};               ///< point: metres
  /// Directional: irradiance on a surface facing the light [W/m²] per band.
  /// Point: radiant intensity [W/sr] per band. A light that follows a candle takes its colour and its
  /// flicker from the flame (sceneAtTime): only the luminance of what is set here counts.
  glm::vec3 intensity{1.0f};
  bool castsShadows = true;
  /// Point: index in Scene::objects of the candle field whose flame the light sits at, following
  /// it as the candle burns down (preset key "follow"); −1: the light stays at `position`.
  int follow = -1;
};

struct Camera {
  bool orthographic = false;
  glm::vec3 position{0.0f, 0.5f, 1.0f};
  glm::vec3 target{0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float fovYDeg = 35.0f;      ///< perspective: vertical field of view
  float orthoHeight = 1.0f;   ///< orthographic: height of the view in metres
};

/// An environment map lighting the scene as M directional lights (preset key "environment";
/// sss/maps/environment_lights.h has the mapping convention and the sampling).
struct Environment {
  std::filesystem::path file;  ///< Radiance .hdr, lat-long; absolute once loaded
  int lights = 16;             ///< M, the number of directional lights it becomes
  float rotationDeg = 0;       ///< turn about +y, counter-clockwise seen from above
  float scale = 1;             ///< multiplies the map's radiance (preset key "intensity")
};

struct Scene {
  std::string name;
  std::string description;
  std::filesystem::path sourcePath;  ///< the preset file it came from, if any
  std::vector<SceneObject> objects;
  std::vector<Light> lights;
  std::optional<Environment> environment;
  /// Directions of the scattered radiosity maps' cameras (unit, from the objects toward the
  /// camera), preset key "map_directions"; empty: K Halton directions (sss.maps).
  std::vector<glm::vec3> mapDirections;
  Camera camera;
  glm::vec3 ambient{0.0f};     ///< uniform sky radiance [W/(m²·sr)] lighting opaque surfaces
  glm::vec3 background{0.0f};  ///< radiance of pixels that hit nothing
  float durationS = 0.0f;      ///< animation length in seconds; 0 = static scene
  bool loop = true;
  float startS = 0.0f;         ///< time of the first frame of `capture` and `view` unless --time is given
  /// flame.flicker: how much a candle's flame flickers (geometry/candle_flame.h): 0 steady, 1 gentle.
  float flameFlicker = 0.0f;
};

}  // namespace tallow::sss
