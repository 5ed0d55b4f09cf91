#include "sss/field_source.h"

#include <algorithm>
#include <stdexcept>

#include "geometry/blob_field.h"
#include "geometry/candle_field.h"
#include "geometry/candle_flame.h"
#include "geometry/mesh_level_set_field.h"
#include "geometry/ply_reader.h"
#include "sss/scene_geometry.h"

namespace tallow::sss {

namespace {
constexpr int kMeshLevelSetResolution = 128;  // voxels across a mesh field's largest extent
}  // namespace

geometry::CandleParams candleParams(const FieldDesc& desc) {
  geometry::CandleParams p;
  p.durationS = desc.candleDurationS;
  p.timeScale = desc.candleTimeScale;
  p.dripCount = desc.candleDrips;
  p.seed = desc.candleSeed;
  return p;
}

namespace {
/// How far (metres) a mesh vertex of the pool's flat surface may stand off it and still be liquid:
/// half a lattice cell at the candle's default 128³ (0.59 mm cells) covers what dual contouring's
/// vertex placement does at the pool's edge, and is well below the rim.
constexpr float kLiquidTolerance = 0.0003f;
double luminance(glm::dvec3 rgb) { return 0.2126 * rgb.x + 0.7152 * rgb.y + 0.0722 * rgb.z; }
}  // namespace

FollowedFlame followedFlame(const Scene& scene, const Light& light, double timeS) {
  const SceneObject& o = scene.objects.at(static_cast<std::size_t>(light.follow));
  if (o.shape != ShapeKind::Field || o.field.kind != FieldKind::Candle)
    throw std::invalid_argument("a light follows object \"" + o.name + "\", which is not a candle field");
  FollowedFlame f;
  f.model = SceneGeometry::modelMatrix(o, geometry::Aabb{});
  f.scale = glm::length(glm::vec3(f.model * glm::vec4(0.0f, 1.0f, 0.0f, 0.0f)));  // world per field unit
  f.flame = geometry::candleFlameAt(geometry::CandleField(timeS, candleParams(o.field)), scene.flameFlicker);
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
    if (!o.liquidMaterial || o.shape != ShapeKind::Field || o.field.kind != FieldKind::Candle) continue;
    const geometry::CandleField candle(timeS, candleParams(o.field));
    if (candle.poolDepth() > 0.0 && candle.poolRadius() > 0.0)
      o.liquidRegion = glm::vec4(static_cast<float>(candle.poolY()), static_cast<float>(candle.poolRadius()),
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

struct FieldSource::Parts {
  FieldDesc desc;
  std::unique_ptr<geometry::MeshLevelSetField> mesh;  ///< mesh fields: built once
  geometry::Aabb bounds;                              ///< field units, contains the surface at every t

  geometry::BlobParams blobParams() const {
    geometry::BlobParams p;
    p.scale = desc.blobScale;
    return p;
  }
  geometry::MeltParams meltParams() const {
    geometry::MeltParams p;
    p.durationS = desc.meltDurationS;
    return p;
  }
  bool melts() const { return desc.kind == FieldKind::Mesh && desc.meltDurationS > 0.0; }
  geometry::CandleParams candleParams() const { return sss::candleParams(desc); }
};

FieldSource::FieldSource(const SceneObject& o) : parts_(std::make_unique<Parts>()) {
  if (o.shape != ShapeKind::Field) throw std::invalid_argument("FieldSource: object \"" + o.name + "\" is not a field");
  Parts& p = *parts_;
  p.desc = o.field;
  switch (o.field.kind) {
    case FieldKind::Blob: p.bounds = geometry::BlobField(0.0, p.blobParams()).bounds(); break;
    case FieldKind::Candle:
      // Every t: the lattice over it holds still, so wax that does not change keeps its vertices.
      p.bounds = geometry::CandleField::lifetimeBounds(p.candleParams());
      break;
    case FieldKind::Mesh: {
      // As a mesh object: largest extent `scale` metres, bottom centre at the origin.
      geometry::TriangleMesh mesh = geometry::readPly(o.field.meshPath);
      const SceneGeometry::MeshPlacement placed = SceneGeometry::meshPlacement(mesh, o.transform.scale, o.field.meshPath);
      for (glm::vec3& v : mesh.positions) v = (v - placed.anchor) * placed.factor;
      p.mesh = std::make_unique<geometry::MeshLevelSetField>(mesh, kMeshLevelSetResolution);
      p.bounds = p.mesh->bounds();
      if (p.melts()) {
        // Slumping widens and the puddle spreads monotonically in t, while the top only sinks:
        // the boxes at t = 0 and fully melted hold every state between (the melted box holds every
        // smoothing level's), padded by two voxels as before. The melt's static grids are built
        // here, once per preset load.
        const geometry::MeltParams melt = p.meltParams();
        const geometry::Aabb end = p.mesh->melted(melt.durationS, melt).bounds();
        p.bounds.extend(end.min);
        p.bounds.extend(end.max);
        const auto pad = static_cast<float>(2.0 * p.mesh->voxelSize());
        p.bounds.min -= glm::vec3(pad);
        p.bounds.max += glm::vec3(pad);
      }
      break;
    }
  }
}

FieldSource::~FieldSource() = default;
FieldSource::FieldSource(FieldSource&&) noexcept = default;
FieldSource& FieldSource::operator=(FieldSource&&) noexcept = default;

bool fieldAnimated(const FieldDesc& desc) { return desc.kind != FieldKind::Mesh || desc.meltDurationS > 0.0; }

bool FieldSource::animated() const { return fieldAnimated(parts_->desc); }
FieldKind FieldSource::kind() const { return parts_->desc.kind; }

geometry::Aabb FieldSource::bounds() const { return parts_->bounds; }

std::unique_ptr<geometry::ScalarField> FieldSource::at(double timeS) const {
  switch (parts_->desc.kind) {
    case FieldKind::Blob: return std::make_unique<geometry::BlobField>(timeS, parts_->blobParams());
    case FieldKind::Candle: return std::make_unique<geometry::CandleField>(timeS, parts_->candleParams());
    case FieldKind::Mesh:
      if (parts_->melts()) return std::make_unique<geometry::MeshLevelSetField>(parts_->mesh->melted(timeS, parts_->meltParams()));
      return std::make_unique<geometry::MeshLevelSetField>(*parts_->mesh);  // shares the grid
  }
  throw std::logic_error("FieldSource: unknown field kind");
}

geometry::SampledLattice FieldSource::sample(double timeS, int n) const {
  const std::unique_ptr<geometry::ScalarField> field = at(timeS);
  // The blob's, the candle's and a melting mesh's lattice covers the box of every t (the blob's own
  // bounds are that box already); a still mesh is sampled over its own narrow band.
  if (parts_->desc.kind != FieldKind::Mesh || parts_->melts()) return geometry::sampleField(*field, parts_->bounds, n);
  return geometry::sampleField(*field, n);
}

bool FieldSource::evaluatedOnGpu() const {
  return parts_->desc.kind == FieldKind::Blob || parts_->desc.kind == FieldKind::Candle;
}

std::optional<geometry::BlobField> FieldSource::blobAt(double timeS) const {
  if (parts_->desc.kind != FieldKind::Blob) return std::nullopt;
  return geometry::BlobField(timeS, parts_->blobParams());
}

std::optional<geometry::CandleField> FieldSource::candleAt(double timeS) const {
  if (parts_->desc.kind != FieldKind::Candle) return std::nullopt;
  return geometry::CandleField(timeS, parts_->candleParams());
}

geometry::SampledLattice FieldSource::gpuLattice(double /*timeS*/, int n) const {
  // As sample() over the same box.
  switch (parts_->desc.kind) {
    case FieldKind::Blob: return geometry::latticeOver(parts_->bounds, n);
    case FieldKind::Candle: return geometry::latticeOver(parts_->bounds, n);
    case FieldKind::Mesh: break;
  }
  throw std::logic_error("FieldSource::gpuLattice: a mesh field is sampled on the CPU");
}

std::optional<geometry::MeltAt> FieldSource::meltAt(double timeS) const {
  if (!parts_->melts()) return std::nullopt;
  return parts_->mesh->meltAt(timeS, parts_->meltParams());
}

geometry::SampledLattice FieldSource::meltLattice(int n) const {
  if (!parts_->melts()) throw std::logic_error("FieldSource::meltLattice: not a melting mesh field");
  return geometry::latticeOver(parts_->bounds, n);  // as sample() over the same box
}

}  // namespace tallow::sss
