// A triangle mesh turned into a level set (geometry::MeshLevelSetField), still or melting: a still
// mesh is sampled on the CPU over its level set's box and uploaded; a melting one is evaluated on
// the GPU from its static NanoVDB grids, uploaded at the first fill, and the melt's scalars at t
// (geometry::GpuMeltField, shaders/fields/melt.glsl).
#include <memory>

#include "geometry/gpu_melt_field.h"
#include "geometry/mesh_level_set_field.h"
#include "geometry/ply_reader.h"
#include "sss/field_kind.h"
#include "sss/scene_geometry.h"

namespace tallow::sss::field_kinds {

bool meshMelts(const FieldDesc& desc) { return desc.meltDurationS > 0.0; }

namespace {

constexpr int kMeshLevelSetResolution = 128;  // voxels across a mesh field's largest extent

/// The level set of `object`'s mesh placed as a mesh object: largest extent `scale` metres, bottom
/// centre at the origin.
std::unique_ptr<geometry::MeshLevelSetField> placedLevelSet(const SceneObject& object) {
  geometry::TriangleMesh mesh = geometry::readPly(object.field.meshPath);
  const SceneGeometry::MeshPlacement placed =
      SceneGeometry::meshPlacement(mesh, object.transform.scale, object.field.meshPath);
  for (glm::vec3& v : mesh.positions) v = (v - placed.anchor) * placed.factor;
  return std::make_unique<geometry::MeshLevelSetField>(mesh, kMeshLevelSetResolution);
}

class StillMeshKind final : public FieldKindModel {
 public:
  explicit StillMeshKind(const SceneObject& object) : mesh_(placedLevelSet(object)) {}
  bool animated() const override { return false; }
  geometry::Aabb bounds() const override { return mesh_->bounds(); }
  std::unique_ptr<geometry::ScalarField> at(double /*timeS*/) const override {
    return std::make_unique<geometry::MeshLevelSetField>(*mesh_);  // shares the grid
  }

 private:
  std::unique_ptr<geometry::MeshLevelSetField> mesh_;
};

class MeltingMeshKind final : public FieldKindModel {
 public:
  MeltingMeshKind(const SceneObject& object) : mesh_(placedLevelSet(object)) {
    melt_.durationS = object.field.meltDurationS;
    // Slumping widens and the puddle spreads monotonically in t, while the top only sinks: the
    // boxes at t = 0 and fully melted hold every state between (the melted box holds every
    // smoothing level's), padded by two voxels. The melt's static grids are built here, once per
    // preset load.
    bounds_ = mesh_->bounds();
    const geometry::Aabb end = mesh_->melted(melt_.durationS, melt_).bounds();
    bounds_.extend(end.min);
    bounds_.extend(end.max);
    const auto pad = static_cast<float>(2.0 * mesh_->voxelSize());
    bounds_.min -= glm::vec3(pad);
    bounds_.max += glm::vec3(pad);
  }
  bool animated() const override { return true; }
  geometry::Aabb bounds() const override { return bounds_; }
  std::unique_ptr<geometry::ScalarField> at(double timeS) const override {
    return std::make_unique<geometry::MeshLevelSetField>(mesh_->melted(timeS, melt_));
  }
  std::unique_ptr<GpuFieldFill> gpuFill(const gpu::ShaderLibrary& shaders) const override;
  std::optional<geometry::MeltAt> meltAt(double timeS) const override { return mesh_->meltAt(timeS, melt_); }

 private:
  std::unique_ptr<geometry::MeshLevelSetField> mesh_;
  geometry::MeltParams melt_;
  geometry::Aabb bounds_;
};

class MeltFill final : public GpuFieldFill {
 public:
  MeltFill(const gpu::ShaderLibrary& shaders, const MeltingMeshKind& kind) : program_(shaders), kind_(kind) {}
  void fill(double timeS, geometry::GpuDualContouring& dc) override {
    program_.fill(dc, *kind_.meltAt(timeS), geometry::latticeOver(kind_.bounds(), dc.samplesPerAxis()));
  }
  std::size_t bytes() const override { return program_.bytes(); }
  std::size_t staticUploads() const override { return program_.gridUploadCount(); }

 private:
  geometry::GpuMeltField program_;
  const MeltingMeshKind& kind_;
};

std::unique_ptr<GpuFieldFill> MeltingMeshKind::gpuFill(const gpu::ShaderLibrary& shaders) const {
  return std::make_unique<MeltFill>(shaders, *this);
}

}  // namespace

std::unique_ptr<FieldKindModel> makeMesh(const SceneObject& object) {
  if (meshMelts(object.field)) return std::make_unique<MeltingMeshKind>(object);
  return std::make_unique<StillMeshKind>(object);
}

}  // namespace tallow::sss::field_kinds
