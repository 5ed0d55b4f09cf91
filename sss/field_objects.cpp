#include "sss/field_objects.h"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <optional>
#include <stdexcept>

#include "sss/field_source.h"

namespace tallow::sss {

struct FieldObjects::Entry {
  int objectIndex = 0;
  FieldSource source;  ///< the field over time and its bounds (field units, every t)
  std::unique_ptr<geometry::GpuDualContouring> dc;
  std::unique_ptr<GpuFieldFill> fill;  ///< the kind's GPU fill, made at its first lattice on the GPU; null: none
  FieldMeshing meshing;  ///< of the last lattice
  double timeS = std::numeric_limits<double>::quiet_NaN();
  bool pending = false;  ///< sampled (uploaded or filled on the GPU), not extracted yet
  bool extracted = false;
  bool checked = true;   ///< the last extraction's overflow was looked at (growOverflowed)

  Entry(int index, const SceneObject& object) : objectIndex(index), source(object) {}
  bool stale(double t, const FieldMeshing& m) const {
    return dc == nullptr || m != meshing || (source.animated() && t != timeS);
  }
};

FieldMeshing fieldMeshingOf(const RenderSettings& s) {
  return {s.fieldRes, s.fieldPlacement, s.fieldOnGpu, s.fieldExtraction};
}

std::unique_ptr<geometry::GpuDualContouring> makeFieldExtractor(const gpu::ShaderLibrary& shaders,
                                                                const FieldSource& source, const FieldMeshing& m) {
  const geometry::NormalSource normals = m.onGpu ? source.gpuNormals() : geometry::NormalSource::LatticeGradient;
  return std::make_unique<geometry::GpuDualContouring>(shaders, m.res, m.placement, normals, m.extraction);
}

void putFieldLattice(const FieldSource& source, double timeS, geometry::GpuDualContouring& dc, GpuFieldFill* onGpu) {
  // On the GPU: no CPU lattice, no per-frame upload. Otherwise (a still mesh, field.evaluate=cpu)
  // sampled on the CPU and uploaded.
  if (onGpu)
    onGpu->fill(timeS, dc);
  else
    dc.upload(source.sample(timeS, dc.samplesPerAxis()));
}

FieldObjects::FieldObjects(const gpu::ShaderLibrary& shaders, const Scene& scene) : shaders_(shaders) {
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const SceneObject& o = scene.objects[i];
    if (o.shape != ShapeKind::Field) continue;
    entries_.push_back(std::make_unique<Entry>(static_cast<int>(i), o));
  }
}

FieldObjects::~FieldObjects() = default;

bool FieldObjects::any(const Scene& scene) {
  return std::any_of(scene.objects.begin(), scene.objects.end(),
                     [](const SceneObject& o) { return o.shape == ShapeKind::Field; });
}

bool FieldObjects::animated() const {
  return std::any_of(entries_.begin(), entries_.end(), [](const auto& e) { return e->source.animated(); });
}

bool FieldObjects::stale(double timeS, const FieldMeshing& meshing) const {
  return std::any_of(entries_.begin(), entries_.end(), [&](const auto& e) { return e->stale(timeS, meshing); });
}

void FieldObjects::sample(double timeS, const FieldMeshing& meshing, SceneGeometry& geometry) {
  for (auto& e : entries_) {
    if (!e->stale(timeS, meshing)) continue;
    if (!e->dc || e->meshing != meshing) e->dc = makeFieldExtractor(shaders_, e->source, meshing);
    // field.evaluate=cpu: every lattice sampled on the CPU (the path before the GPU fields).
    const bool onGpu = meshing.onGpu;
    if (onGpu && !e->fill) e->fill = e->source.gpuFill(shaders_);  // static data go up at its first fill
    putFieldLattice(e->source, timeS, *e->dc, onGpu ? e->fill.get() : nullptr);
    e->meshing = meshing;
    e->timeS = timeS;
    e->pending = true;
    geometry.attachField(e->objectIndex, e->dc.get(), e->source.bounds());
  }
}

void FieldObjects::extract() {
  for (auto& e : entries_) {
    if (!e->pending) continue;
    e->dc->extract();
    e->pending = false;
    e->extracted = true;
    e->checked = false;
  }
}

void FieldObjects::setVertexCapacity(std::size_t vertices) {
  for (auto& e : entries_)
    if (e->dc) e->dc->setVertexCapacity(vertices);
}

bool FieldObjects::growOverflowed(bool wait) {
  bool grown = false;
  for (auto& e : entries_) {
    if (e->checked || !e->dc) continue;
    const std::optional<bool> over = e->dc->overflowed(wait);
    if (!over) continue;
    e->checked = true;
    if (!*over) continue;
    const std::size_t made = e->dc->generatedTriangles(), held = e->dc->triangleCapacity();
    const std::size_t vertices = e->dc->generatedVertices(), vertexRoom = e->dc->vertexCapacity();
    if (!e->dc->growToFit()) {
      std::fprintf(stderr, "tallow: warning: field object %d: %zu vertices and %zu triangles exceed the dual "
                           "contouring buffers' cap; the mesh is cut\n", e->objectIndex, vertices, made);
      continue;
    }
    std::fprintf(stderr, "tallow: warning: field object %d made %zu vertices and %zu triangles, its buffers held %zu "
                         "and %zu; grown to %zu vertices, the frame drawn again\n",
                 e->objectIndex, vertices, made, vertexRoom, held, e->dc->vertexCapacity());
    e->pending = true;  // the lattice still holds this extraction's field
    grown = true;
  }
  return grown;
}

std::size_t FieldObjects::triangleCount() const {
  std::size_t n = 0;
  for (const auto& e : entries_)
    if (e->extracted) n += e->dc->triangleCount();
  return n;
}

std::optional<std::size_t> FieldObjects::triangleCountIfAvailable() const {
  std::size_t n = 0;
  for (const auto& e : entries_)
    if (e->extracted) {
      const std::optional<std::size_t> count = e->dc->triangleCountIfAvailable();
      if (!count) return std::nullopt;
      n += *count;
    }
  return n;
}

std::size_t FieldObjects::bytes() const {
  std::size_t n = 0;
  for (const auto& e : entries_) {
    if (e->dc) n += e->dc->bufferBytes();
    if (e->fill) n += e->fill->bytes();
  }
  return n;
}

std::size_t FieldObjects::meltGridUploads() const {
  std::size_t n = 0;
  for (const auto& e : entries_)
    if (e->fill) n += e->fill->staticUploads();
  return n;
}

}  // namespace tallow::sss
