#include "sss/field_source.h"

#include <stdexcept>

#include "geometry/candle_flame.h"
#include "sss/scene_geometry.h"

namespace tallow::sss {

geometry::CandleParams candleParams(const FieldDesc& desc) { return field_kinds::candleParams(desc); }

namespace {
/// How far (metres) a mesh vertex of the pool's flat surface may stand off it and still be liquid:
/// half a lattice cell at the candle's default 128³ (0.59 mm cells) covers what dual contouring's
/// vertex placement does at the pool's edge, and is well below the rim.
constexpr float kLiquidTolerance = 0.0003f;
double luminance(glm::dvec3 rgb) { return 0.2126 * rgb.x + 0.7152 * rgb.y + 0.0722 * rgb.z; }
}  // namespace

FollowedFlame followedFlame(const Scene& scene, const Light& light, double timeS) {
  const SceneObject& o = scene.objects.at(static_cast<std::size_t>(light.follow));
  const std::optional<geometry::CandleField> candle =
      o.shape == ShapeKind::Field ? candleOf(o.field, timeS) : std::nullopt;
  if (!candle) throw std::invalid_argument("a light follows object \"" + o.name + "\", which is not a candle field");
  FollowedFlame f;
  f.model = SceneGeometry::modelMatrix(o, geometry::Aabb{});
  f.scale = glm::length(glm::vec3(f.model * glm::vec4(0.0f, 1.0f, 0.0f, 0.0f)));  // world per field unit
  f.flame = geometry::candleFlameAt(*candle, scene.flameFlicker);
  f.emission = geometry::flameEmission(f.flame);
  return f;
}

glm::dvec3 FollowedFlame::intensity(const Light& preset) const {
  // The flame's flux in the light's luminance, with the flicker's gain: the colour is the flame's.
  return emission.flux * (luminance(glm::dvec3(preset.intensity)) * flame.gain / emission.luminance());
}

double FollowedFlame::radianceScale(const Light& placed) const {
  // The flux is in field units (m² before the transform): scale² turns it into world m².
  return luminance(glm::dvec3(placed.intensity)) / (emission.luminance() * double(scale) * double(scale));
}

Scene sceneAtTime(const Scene& scene, double timeS) {
  Scene out = scene;
  // A candle's melt pool at t: where its liquid surface is (shaders/materials/liquid_surface.glsl).
  for (SceneObject& o : out.objects) {
    o.liquidRegion = glm::vec4(0.0f);
    if (!o.liquidMaterial || o.shape != ShapeKind::Field) continue;
    const std::optional<geometry::CandleField> candle = candleOf(o.field, timeS);
    if (candle && candle->poolDepth() > 0.0 && candle->poolRadius() > 0.0)
      o.liquidRegion = glm::vec4(static_cast<float>(candle->poolY()), static_cast<float>(candle->poolRadius()),
                                 static_cast<float>(geometry::CandleField::meniscus()), kLiquidTolerance);
  }
  for (std::size_t i = 0; i < out.lights.size(); ++i) {
    Light& light = out.lights[i];
    if (light.follow < 0) continue;
    // The light is the drawn flame's emission: its centre, and its flux (colour and flicker included).
    const FollowedFlame f = followedFlame(scene, scene.lights[i], timeS);
    light.position = glm::vec3(f.model * glm::vec4(glm::vec3(f.emission.centre), 1.0f));
    light.intensity = glm::vec3(f.intensity(scene.lights[i]));
  }
  return out;
}

FieldSource::FieldSource(const SceneObject& o) : kind_(makeFieldKind(o)) {}
FieldSource::~FieldSource() = default;
FieldSource::FieldSource(FieldSource&&) noexcept = default;
FieldSource& FieldSource::operator=(FieldSource&&) noexcept = default;

}  // namespace tallow::sss
