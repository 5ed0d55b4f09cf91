#pragma once
// One field object (ShapeKind::Field) of a scene as a source of scalar fields over time: the
// time-independent parts are built once (a mesh field's level set, the bounds), and at(t) gives the
// field at time t in field units (before the object's transform, SceneGeometry::modelMatrix).
// The renderer (FieldObjects) and the `tallow mesh` / `tallow field` commands all go through this
// class, so they sample and evaluate exactly the same numbers.
#include <memory>
#include <optional>

#include "geometry/blob_field.h"
#include "geometry/candle_field.h"
#include "geometry/candle_flame.h"
#include "geometry/grid_sampler.h"
#include "geometry/mesh_melt.h"
#include "geometry/scalar_field.h"
#include "geometry/triangle_mesh.h"
#include "sss/scene.h"

namespace tallow::sss {

/// The candle of a FieldKind::Candle description (what FieldSource builds it with).
geometry::CandleParams candleParams(const FieldDesc& desc);

/// True when a field of this description changes with t (blob, candle, a mesh field that melts).
bool fieldAnimated(const FieldDesc& desc);

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
  /// ShapeKind::Field). Throws std::runtime_error naming the file when a mesh field's file is
  /// missing or broken, std::invalid_argument when `object` is not a field object.
  explicit FieldSource(const SceneObject& object);
  ~FieldSource();
  FieldSource(FieldSource&&) noexcept;
  FieldSource& operator=(FieldSource&&) noexcept;

  /// True when the field changes with t (blob, candle, a mesh field with melt_s > 0).
  bool animated() const;
  FieldKind kind() const;
  /// Field units: contains the surface at every t (what the renderer's bounds are fitted to).
  geometry::Aabb bounds() const;
  /// The field at time t (seconds), field units; value < 0 inside (geometry::ScalarField).
  std::unique_ptr<geometry::ScalarField> at(double timeS) const;
  /// at(t) sampled on n³ points over the box the renderer isosurfaces for this kind of field.
  geometry::SampledLattice sample(double timeS, int n) const;
  /// True for the fields the renderer evaluates on the GPU from uniforms (blob, candle:
  /// geometry::GpuBlobField, GpuCandleField) instead of sample() + upload; mesh fields are sampled.
  bool evaluatedOnGpu() const;
  /// A blob field (FieldKind::Blob) at time t; std::nullopt for the other kinds.
  std::optional<geometry::BlobField> blobAt(double timeS) const;
  /// A candle field (FieldKind::Candle) at time t; std::nullopt for the other kinds.
  std::optional<geometry::CandleField> candleAt(double timeS) const;
  /// The lattice sample(t, n) fills, without values: where the GPU evaluates a field for which
  /// evaluatedOnGpu() (a blob, a candle: the box of every t, so the lattice holds still). Throws
  /// std::logic_error for the other kinds.
  geometry::SampledLattice gpuLattice(double timeS, int n) const;

  /// A melting mesh field's melt at time t (its static NanoVDB grids, built once, and the scalars
  /// at t), which the renderer evaluates on the GPU (geometry::GpuMeltField) instead of sample();
  /// std::nullopt for the other kinds and for a mesh that does not melt.
  std::optional<geometry::MeltAt> meltAt(double timeS) const;
  /// The lattice sample(t, n) fills for a melting mesh (the box of every t), without values: where
  /// the GPU evaluates meltAt(t). Throws std::logic_error for the other kinds.
  geometry::SampledLattice meltLattice(int n) const;

  struct Parts;  ///< per kind, in field_source.cpp

 private:
  std::unique_ptr<Parts> parts_;
};

}  // namespace tallow::sss
