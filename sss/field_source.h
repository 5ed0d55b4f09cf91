#pragma once
// One field object (ShapeKind::Field) of a scene as a source of scalar fields over time: the
// time-independent parts are built once (a mesh field's level set, the bounds), and at(t) gives the
// field at time t in field units (before the object's transform, SceneGeometry::modelMatrix).
// The renderer (FieldObjects) and the `tallow mesh` / `tallow field` commands all go through this
// class, so they sample and evaluate exactly the same numbers; what differs by kind is the kind's
// plug-in (sss/field_kind.h).
#include <memory>
#include <optional>

#include "geometry/blob_field.h"
#include "geometry/candle_field.h"
#include "geometry/candle_flame.h"
#include "geometry/grid_sampler.h"
#include "geometry/mesh_melt.h"
#include "geometry/scalar_field.h"
#include "geometry/triangle_mesh.h"
#include "sss/field_kind.h"
#include "sss/scene.h"

namespace tallow::sss {

/// The candle of a candle field's description (what its kind builds it with).
geometry::CandleParams candleParams(const FieldDesc& desc);

/// A light that follows a candle (Light::follow) at time t: the candle, its flame
/// (geometry::candleFlameAt with scene.flameFlicker) and what it emits. Throws std::invalid_argument
/// when the object followed is not a candle field.
struct FollowedFlame {
  glm::mat4 model{1.0f};  ///< the candle's object → world transform
  float scale = 1.0f;     ///< world units per field unit
  geometry::CandleFlame flame;      ///< field units
  geometry::FlameEmission emission;  ///< field units

  /// The light's intensity [W/sr] per band: the flame's flux, in the luminance of the preset's
  /// light (`preset`, as loaded) times the flicker's gain.
  glm::dvec3 intensity(const Light& preset) const;
  /// The drawn flame's world radiance per unit of flameProfile, for the light as sceneAtTime placed
  /// it: the flame's flux then carries exactly the light's intensity.
  double radianceScale(const Light& placed) const;
};
FollowedFlame followedFlame(const Scene& scene, const Light& light, double timeS);

/// The scene at time t: every light that follows a candle's flame (Light::follow) is the flame's
/// emission under its object's transform — at its emission centre, its intensity the flame's flux
/// (the blackbody colour of the drawn flame, the luminance of the light's own intensity, the
/// flicker's gain); otherwise `scene` unchanged.
Scene sceneAtTime(const Scene& scene, double timeS);

class FieldSource {
 public:
  /// Builds the time-independent parts of field object `object` (object.shape must be
  /// ShapeKind::Field) through its kind (makeFieldKind). Throws std::runtime_error naming the file
  /// when a mesh field's file is missing or broken, std::invalid_argument when `object` is not a
  /// field object.
  explicit FieldSource(const SceneObject& object);
  ~FieldSource();
  FieldSource(FieldSource&&) noexcept;
  FieldSource& operator=(FieldSource&&) noexcept;

  /// True when the field changes with t (blob, candle, a mesh field with melt_s > 0).
  bool animated() const { return kind_->animated(); }
  /// Field units: contains the surface at every t (what the renderer's bounds are fitted to).
  geometry::Aabb bounds() const { return kind_->bounds(); }
  /// The field at time t (seconds), field units; value < 0 inside (geometry::ScalarField).
  std::unique_ptr<geometry::ScalarField> at(double timeS) const { return kind_->at(timeS); }
  /// at(t) sampled on n³ points over bounds(): the lattice the renderer isosurfaces.
  geometry::SampledLattice sample(double timeS, int n) const { return kind_->sample(timeS, n); }
  /// The lattice a GPU fill (gpuFill) writes at n³ points, without values: the box of every t, so
  /// that it holds still while the field moves; what sample() fills for the kinds that have a fill.
  geometry::SampledLattice gpuLattice(int n) const { return geometry::latticeOver(bounds(), n); }
  /// The extractor's vertex normals when the field is evaluated on the GPU.
  geometry::NormalSource gpuNormals() const { return kind_->gpuNormals(); }
  /// What evaluates this field on the GPU from uniforms at t (blob, candle, a melting mesh), or
  /// nullptr for a field sampled on the CPU and uploaded (a still mesh). Lives no longer than this.
  std::unique_ptr<GpuFieldFill> gpuFill(const gpu::ShaderLibrary& shaders) const { return kind_->gpuFill(shaders); }

  /// The kind's own model at t where it is that kind; std::nullopt otherwise.
  std::optional<geometry::BlobField> blobAt(double timeS) const { return kind_->blobAt(timeS); }
  std::optional<geometry::CandleField> candleAt(double timeS) const { return kind_->candleAt(timeS); }
  std::optional<geometry::MeltAt> meltAt(double timeS) const { return kind_->meltAt(timeS); }

 private:
  std::unique_ptr<FieldKindModel> kind_;
};

}  // namespace tallow::sss
