#pragma once
// The field objects of a scene (ShapeKind::Field): each frame whose time (or field.res) changed,
// the field at that time is put on a lattice and isosurfaced on the GPU by GpuDualContouring;
// otherwise the last transform-feedback mesh is drawn again. The analytic fields' lattices are
// filled on the GPU from uniforms at t — the blob's centres (geometry::GpuBlobField,
// shaders/fields/blob.glsl), the candle's shape (geometry::GpuCandleField, shaders/fields/candle.glsl)
// — and their normals come from their analytic gradients; a melting mesh's from its static NanoVDB
// grids, uploaded once, and the melt's scalars at t (geometry::GpuMeltField, shaders/fields/melt.glsl);
// still mesh fields are sampled on the CPU and uploaded. Each object's field, bounds, sampling and
// GPU fill come from its sss::FieldSource (shared with `tallow mesh` / `field`), i.e. from its
// kind's plug-in (sss/field_kind.h): nothing here names a kind.
#include <memory>
#include <optional>
#include <vector>

#include "geometry/gpu_dual_contouring.h"
#include "geometry/scalar_field.h"
#include "gpu/shader_library.h"
#include "sss/field_kind.h"
#include "sss/render_settings.h"
#include "sss/scene.h"
#include "sss/scene_geometry.h"

namespace tallow::sss {

class FieldSource;

/// How field objects are sampled and contoured: the field.* parameters.
struct FieldMeshing {
  int res = 64;                                                              ///< field.res
  geometry::VertexPlacement placement = geometry::kDefaultPlacement;         ///< field.placement
  bool onGpu = true;                                                         ///< field.evaluate
  geometry::ExtractionPath extraction = geometry::kDefaultExtraction;        ///< field.extraction
  bool operator==(const FieldMeshing&) const = default;
};
FieldMeshing fieldMeshingOf(const RenderSettings& settings);

/// An extractor for `source` as the renderer makes it (res³ samples, the placement and stages
/// asked): the vertex normals the field's kind gives when it is evaluated on the GPU (`onGpu`,
/// field.evaluate; the analytic gradient of a blob or a candle), otherwise from the lattice.
std::unique_ptr<geometry::GpuDualContouring> makeFieldExtractor(const gpu::ShaderLibrary& shaders,
                                                                const FieldSource& source, const FieldMeshing& meshing);

/// Puts `source`'s field at t on `dc`'s lattice, as the renderer does: with `onGpu` (its kind's
/// FieldSource::gpuFill, made by the caller; nullptr with field.evaluate=cpu or for a kind without
/// one) from uniforms and one dispatch, otherwise sampled on the CPU and uploaded.
void putFieldLattice(const FieldSource& source, double timeS, geometry::GpuDualContouring& dc,
                     GpuFieldFill* onGpu);

class FieldObjects {
 public:
  /// Builds the time-independent parts (a mesh field's level set). Throws std::runtime_error
  /// naming the file when a mesh field's file is missing or broken.
  FieldObjects(const gpu::ShaderLibrary& shaders, const Scene& scene);
  ~FieldObjects();

  static bool any(const Scene& scene);
  /// True when some field object changes with time.
  bool animated() const;
  bool empty() const { return entries_.empty(); }
  /// True when some field must be sampled and extracted again for time t with `meshing`: nothing
  /// extracted yet, a field.* parameter changed, or t changed for an animated field.
  bool stale(double timeS, const FieldMeshing& meshing) const;
  /// The lattice at t of every stale field (pass "field.sample"): a blob's or a candle's filled on
  /// the GPU (the CPU only sets uniforms and dispatches), a melting mesh's too (its grids uploaded at
  /// its first fill), a still mesh field's sampled on the CPU and uploaded; with onGpu = false
  /// (field.evaluate=cpu) every field's sampled on the CPU and uploaded, normals from the lattice;
  /// re-attaches the extractors to `geometry` (call geometry.update afterwards).
  void sample(double timeS, const FieldMeshing& meshing, SceneGeometry& geometry);
  /// GPU extraction of every field sampled by the last sample() (pass "field.extract").
  void extract();
  /// Transform-feedback overflow on the render path (issue 38): for each field whose last
  /// extraction is not checked yet and whose counts are available (`wait`: waits for them), when its
  /// buffers held fewer vertices or triangles than it made, grows them to fit, says so on stderr in
  /// one line and marks the field to be extracted again from the same lattice. True when some field
  /// was grown: the frame that drew it was cut, and must be drawn again.
  bool growOverflowed(bool wait);
  /// Sizes every extractor's buffers for `vertices` (GpuDualContouring::setVertexCapacity): what
  /// growOverflowed starts from; for tests of the overflow.
  void setVertexCapacity(std::size_t vertices);
  /// Triangles of the last extractions. Reads a transform-feedback query, so it waits for the
  /// GPU to finish the last extraction (a stall): for stats, not for the frame loop.
  std::size_t triangleCount() const;
  /// triangleCount without a wait: nullopt while an extraction is still on the GPU.
  std::optional<std::size_t> triangleCountIfAvailable() const;
  std::size_t bytes() const;
  /// Uploads of the fields' static GPU data so far (a melting mesh's grids: one per renderer).
  std::size_t meltGridUploads() const;

  struct Entry;

 private:
  const gpu::ShaderLibrary& shaders_;
  std::vector<std::unique_ptr<Entry>> entries_;
};

}  // namespace tallow::sss
