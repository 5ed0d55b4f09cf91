#include "sss/field_objects.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/blob_field.h"
#include "geometry/candle_field.h"
#include "geometry/grid_sampler.h"
#include "geometry/mesh_level_set_field.h"
#include "geometry/ply_reader.h"

namespace tallow::sss {

namespace {
constexpr int kMeshLevelSetResolution = 128;  // voxels across a mesh field's largest extent
constexpr float kCandleMargin = 0.25f;        // × radius around the t = 0 candle: room for drips
}  // namespace

struct FieldObjects::Entry {
  int objectIndex = 0;
  FieldDesc desc;
  std::unique_ptr<geometry::MeshLevelSetField> mesh;  ///< mesh fields: built once
  geometry::Aabb bounds;                              ///< field units, contains the surface at every t
  std::unique_ptr<geometry::GpuDualContouring> dc;
  int res = 0;
  double timeS = std::numeric_limits<double>::quiet_NaN();
  bool pending = false;  ///< sampled and uploaded, not extracted yet
  bool extracted = false;

  bool animated() const { return desc.kind != FieldKind::Mesh; }
  bool stale(double t, int r) const { return dc == nullptr || r != res || (animated() && t != timeS); }

  geometry::BlobParams blobParams() const {
    geometry::BlobParams p;
    p.scale = desc.blobScale;
    return p;
  }
  geometry::CandleParams candleParams() const {
    geometry::CandleParams p;
    p.durationS = desc.candleDurationS;
    return p;
  }
};

FieldObjects::FieldObjects(const gpu::ShaderLibrary& shaders, const Scene& scene) : shaders_(shaders) {
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const SceneObject& o = scene.objects[i];
    if (o.shape != ShapeKind::Field) continue;
    auto e = std::make_unique<Entry>();
    e->objectIndex = static_cast<int>(i);
    e->desc = o.field;
    switch (o.field.kind) {
      case FieldKind::Blob: e->bounds = geometry::BlobField(0.0, e->blobParams()).bounds(); break;
      case FieldKind::Candle: {
        const geometry::CandleParams params = e->candleParams();
        e->bounds = geometry::CandleField(0.0, params).bounds();  // the tallest candle
        const float m = kCandleMargin * static_cast<float>(params.radius);
        e->bounds.min -= glm::vec3(m, 0.0f, m);
        e->bounds.max += glm::vec3(m, 0.0f, m);
        break;
      }
      case FieldKind::Mesh: {
        // As a mesh object: largest extent `scale` metres, bottom centre at the origin.
        geometry::TriangleMesh mesh = geometry::readPly(o.field.meshPath);
        const geometry::Aabb b = mesh.bounds();
        const glm::vec3 size = b.size();
        const float extent = std::max(size.x, std::max(size.y, size.z));
        const float s = extent > 0.0f ? o.transform.scale / extent : 1.0f;
        const glm::vec3 anchor(b.centre().x, b.min.y, b.centre().z);
        for (glm::vec3& p : mesh.positions) p = (p - anchor) * s;
        e->mesh = std::make_unique<geometry::MeshLevelSetField>(mesh, kMeshLevelSetResolution);
        e->bounds = e->mesh->bounds();
        break;
      }
    }
    entries_.push_back(std::move(e));
  }
}

FieldObjects::~FieldObjects() = default;

bool FieldObjects::any(const Scene& scene) {
  return std::any_of(scene.objects.begin(), scene.objects.end(),
                     [](const SceneObject& o) { return o.shape == ShapeKind::Field; });
}

bool FieldObjects::stale(double timeS, int res) const {
  return std::any_of(entries_.begin(), entries_.end(), [&](const auto& e) { return e->stale(timeS, res); });
}

void FieldObjects::sample(double timeS, int res, SceneGeometry& geometry) {
  for (auto& e : entries_) {
    if (!e->stale(timeS, res)) continue;
    if (!e->dc || e->res != res) e->dc = std::make_unique<geometry::GpuDualContouring>(shaders_, res);
    geometry::SampledLattice lattice;
    switch (e->desc.kind) {
      case FieldKind::Blob: lattice = geometry::sampleField(geometry::BlobField(timeS, e->blobParams()), e->bounds, res); break;
      case FieldKind::Candle: lattice = geometry::sampleField(geometry::CandleField(timeS, e->candleParams()), res); break;
      case FieldKind::Mesh: lattice = geometry::sampleField(*e->mesh, res); break;
    }
    e->dc->upload(lattice);
    e->res = res;
    e->timeS = timeS;
    e->pending = true;
    geometry.attachField(e->objectIndex, e->dc.get(), e->bounds);
  }
}

void FieldObjects::extract() {
  for (auto& e : entries_) {
    if (!e->pending) continue;
    e->dc->extract();
    e->pending = false;
    e->extracted = true;
  }
}

std::size_t FieldObjects::triangleCount() const {
  std::size_t n = 0;
  for (const auto& e : entries_)
    if (e->extracted) n += e->dc->triangleCount();
  return n;
}

std::size_t FieldObjects::bytes() const {
  std::size_t n = 0;
  for (const auto& e : entries_)
    if (e->dc) n += e->dc->bufferBytes();
  return n;
}

}  // namespace tallow::sss
