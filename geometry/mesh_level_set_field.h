#pragma once
// Any triangle mesh as a narrow-band level set (issue 4, point 1): OpenVDB's mesh-to-volume
// (tools::meshToLevelSet), so imported shapes go through the same path as the procedural fields.
// OpenVDB stays inside mesh_level_set_field.cpp.
#include "geometry/scalar_field.h"
#include "geometry/triangle_mesh.h"

#include <memory>

namespace tallow::geometry {

namespace detail {
struct MeshLevelSetGrid;  // the OpenVDB FloatGrid, in mesh_level_set_field.cpp (pimpl)
}

class MeshLevelSetField final : public ScalarField {
 public:
  /// Voxel size = largest extent of mesh.bounds() / resolution; the band is bandVoxels voxels on
  /// each side of the surface. Holes (loops of edges used by one triangle, as in a scan) are
  /// first closed with a fan around each loop's centroid, since OpenVDB finds the inside by
  /// flood fill from the outside, which leaks through holes. Throws std::invalid_argument for an empty mesh, resolution < 8 or
  /// bandVoxels < 3.
  explicit MeshLevelSetField(const TriangleMesh& mesh, int resolution = 128, double bandVoxels = 3.0);
  ~MeshLevelSetField() override;
  MeshLevelSetField(const MeshLevelSetField&);
  MeshLevelSetField& operator=(const MeshLevelSetField&);

  /// Trilinear (box) sample of the level set, metres; outside the narrow band ± the band width.
  double value(glm::dvec3 p) const override;
  /// Central differences of value() with a step of half a voxel.
  glm::dvec3 gradient(glm::dvec3 p) const override;
  /// World box of the active voxels (the narrow band), so it contains the whole surface.
  Aabb bounds() const override;

  double voxelSize() const { return voxelSize_; }
  double bandWidth() const { return bandVoxels_ * voxelSize_; }

 private:
  double voxelSize_;
  double bandVoxels_;
  std::shared_ptr<const detail::MeshLevelSetGrid> grid_;
};

}  // namespace tallow::geometry
