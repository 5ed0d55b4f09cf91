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
  std::unique_ptr<geometry::GpuMeltField> melt;  ///< a melting mesh's grids on the GPU, made at its first lattice
  int res = 0;
  geometry::VertexPlacement placement = geometry::kDefaultPlacement;
  bool onGpu = true;  ///< field.evaluate of the last lattice
  double timeS = std::numeric_limits<double>::quiet_NaN();
  bool pending = false;  ///< sampled (uploaded or filled on the GPU), not extracted yet
  bool extracted = false;
  bool checked = true;   ///< the last extraction's overflow was looked at (growOverflowed)

  Entry(int index, const SceneObject& object) : objectIndex(index), source(object) {}
  bool stale(double t, int r, geometry::VertexPlacement p, bool gpu) const {
    return dc == nullptr || r != res || p != placement || gpu != onGpu || (source.animated() && t != timeS);
  }
};

std::unique_ptr<geometry::GpuDualContouring> makeFieldExtractor(const gpu::ShaderLibrary& shaders,
                                                                const FieldSource& source, int n,
                                                                geometry::VertexPlacement placement, bool onGpu) {
  geometry::NormalSource normals = geometry::NormalSource::LatticeGradient;
  if (onGpu && source.kind() == FieldKind::Blob) normals = geometry::NormalSource::BlobGradient;
  if (onGpu && source.kind() == FieldKind::Candle) normals = geometry::NormalSource::CandleGradient;
  return std::make_unique<geometry::GpuDualContouring>(shaders, n, placement, normals);
}

void GpuFieldPrograms::fill(const FieldSource& source, double timeS, geometry::GpuDualContouring& dc) {
  const geometry::SampledLattice frame = source.gpuLattice(timeS, dc.samplesPerAxis());
  if (const std::optional<geometry::BlobField> blob = source.blobAt(timeS)) {
    if (!blob_) blob_ = std::make_unique<geometry::GpuBlobField>(shaders_);
    blob_->fill(dc, *blob, frame);
  } else if (const std::optional<geometry::CandleField> candle = source.candleAt(timeS)) {
    if (!candle_) candle_ = std::make_unique<geometry::GpuCandleField>(shaders_);
    candle_->fill(dc, *candle, frame);
  } else {
    throw std::logic_error("GpuFieldPrograms::fill: not a field evaluated on the GPU");
  }
}

void putFieldLattice(const FieldSource& source, double timeS, geometry::GpuDualContouring& dc,
                     GpuFieldPrograms& onGpu, geometry::GpuMeltField* meltOnGpu) {
  // Analytic fields from their uniforms at t, a melting mesh from its static grids and the melt's
  // scalars at t: no CPU lattice, no per-frame upload. Still mesh fields on the CPU.
  if (source.evaluatedOnGpu()) {
    onGpu.fill(source, timeS, dc);
  } else if (const std::optional<geometry::MeltAt> melt = source.meltAt(timeS)) {
    if (!meltOnGpu) throw std::logic_error("putFieldLattice: a melting mesh field needs a GpuMeltField");
    meltOnGpu->fill(dc, *melt, source.meltLattice(dc.samplesPerAxis()));
  } else
    dc.upload(source.sample(timeS, dc.samplesPerAxis()));
}

FieldObjects::FieldObjects(const gpu::ShaderLibrary& shaders, const Scene& scene) : shaders_(shaders), onGpu_(shaders) {
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

bool FieldObjects::stale(double timeS, int res, geometry::VertexPlacement placement, bool onGpu) const {
  return std::any_of(entries_.begin(), entries_.end(),
                     [&](const auto& e) { return e->stale(timeS, res, placement, onGpu); });
}

void FieldObjects::sample(double timeS, int res, geometry::VertexPlacement placement, bool onGpu,
                          SceneGeometry& geometry) {
  for (auto& e : entries_) {
    if (!e->stale(timeS, res, placement, onGpu)) continue;
    if (!e->dc || e->res != res || e->placement != placement || e->onGpu != onGpu)
      e->dc = makeFieldExtractor(shaders_, e->source, res, placement, onGpu);
    if (onGpu) {
      if (!e->melt && e->source.kind() == FieldKind::Mesh && e->source.animated())
        e->melt = std::make_unique<geometry::GpuMeltField>(shaders_);  // its grids go up at the first fill
      putFieldLattice(e->source, timeS, *e->dc, onGpu_, e->melt.get());
    } else {
      e->dc->upload(e->source.sample(timeS, res));  // field.evaluate=cpu: the path before the GPU fields
    }
    e->res = res;
    e->placement = placement;
    e->onGpu = onGpu;
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

std::size_t FieldObjects::bytes() const {
  std::size_t n = 0;
  for (const auto& e : entries_) {
    if (e->dc) n += e->dc->bufferBytes();
    if (e->melt) n += e->melt->bytes();
  }
  return n;
}

std::size_t FieldObjects::meltGridUploads() const {
  std::size_t n = 0;
  for (const auto& e : entries_)
    if (e->melt) n += e->melt->gridUploadCount();
  return n;
}

}  // namespace tallow::sss
