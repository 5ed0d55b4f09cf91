#pragma once
// One kind of field object (FieldKind: blob, candle, mesh still or melting) as a plug-in: what
// FieldSource, FieldObjects and the commands ask of a field without naming its kind. makeFieldKind
// (field_kind.cpp) is the one place that reads FieldDesc::kind to pick an implementation; the
// implementations are field_kind_blob.cpp, field_kind_candle.cpp and field_kind_mesh.cpp.
#include <cstddef>
#include <memory>
#include <optional>

#include "geometry/blob_field.h"
#include "geometry/candle_field.h"
#include "geometry/gpu_dual_contouring.h"
#include "geometry/grid_sampler.h"
#include "geometry/mesh_melt.h"
#include "geometry/scalar_field.h"
#include "gpu/shader_library.h"
#include "sss/scene.h"

namespace tallow::sss {

/// Fills a GpuDualContouring's lattice with one field at time t on the GPU (uniforms and one
/// dispatch), owning that kind's compute program and whatever static data it uploads at its first
/// fill. Made by FieldKindModel::gpuFill; lives no longer than the model it was made from.
class GpuFieldFill {
 public:
  virtual ~GpuFieldFill() = default;
  virtual void fill(double timeS, geometry::GpuDualContouring& dc) = 0;
  /// GPU memory of the static data this fill uploaded (bytes).
  virtual std::size_t bytes() const { return 0; }
  /// Uploads of static data so far (a melting mesh's grids: one).
  virtual std::size_t staticUploads() const { return 0; }
};

/// The behaviour of one field object over time, in field units (before SceneGeometry::modelMatrix).
class FieldKindModel {
 public:
  virtual ~FieldKindModel() = default;
  /// True when the field changes with t.
  virtual bool animated() const = 0;
  /// Contains the surface at every t (what the renderer's bounds and lattice are fitted to).
  virtual geometry::Aabb bounds() const = 0;
  /// The field at time t (seconds); value < 0 inside (geometry::ScalarField).
  virtual std::unique_ptr<geometry::ScalarField> at(double timeS) const = 0;
  /// at(t) on n³ points over bounds() (geometry::sampleField): what the renderer isosurfaces.
  geometry::SampledLattice sample(double timeS, int n) const;
  /// The extractor's vertex normals when the field is evaluated on the GPU: its analytic gradient
  /// where the kind has one, otherwise the lattice's.
  virtual geometry::NormalSource gpuNormals() const { return geometry::NormalSource::LatticeGradient; }
  /// The fill that evaluates this field on the GPU (field.evaluate=gpu), or nullptr for a kind that
  /// is sampled on the CPU and uploaded.
  virtual std::unique_ptr<GpuFieldFill> gpuFill(const gpu::ShaderLibrary& shaders) const;

  // What a kind exposes of its own model, for the passes and tests that need that model (a flame
  // follows a candle; the GPU tests compare the kind's fill with its CPU field). std::nullopt for
  // the other kinds.
  virtual std::optional<geometry::BlobField> blobAt(double /*timeS*/) const { return std::nullopt; }
  virtual std::optional<geometry::CandleField> candleAt(double /*timeS*/) const { return std::nullopt; }
  virtual std::optional<geometry::MeltAt> meltAt(double /*timeS*/) const { return std::nullopt; }
};

/// Builds the model of field object `object` (object.shape must be ShapeKind::Field). Throws
/// std::runtime_error naming the file when a mesh field's file is missing or broken.
std::unique_ptr<FieldKindModel> makeFieldKind(const SceneObject& object);

// Questions about a description that must not build its model (a mesh field's level set takes
// seconds): answered by the kind's implementation without it.

/// True when a field of this description changes with t (blob, candle, a mesh field that melts).
bool fieldAnimated(const FieldDesc& desc);
/// True when a light may follow a field of this description as its flame (a candle).
bool fieldCarriesFlame(const FieldDesc& desc);
/// The candle of a candle field's description at t; std::nullopt for the other kinds.
std::optional<geometry::CandleField> candleOf(const FieldDesc& desc, double timeS);

// The implementations (one per kind), for makeFieldKind and the description questions above.
namespace field_kinds {
std::unique_ptr<FieldKindModel> makeBlob(const FieldDesc& desc);
std::unique_ptr<FieldKindModel> makeCandle(const FieldDesc& desc);
std::unique_ptr<FieldKindModel> makeMesh(const SceneObject& object);
geometry::CandleParams candleParams(const FieldDesc& desc);
bool meshMelts(const FieldDesc& desc);
}  // namespace field_kinds

}  // namespace tallow::sss
