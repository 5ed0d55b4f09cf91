#pragma once
// Any triangle mesh as a narrow-band level set (issue 4, point 1): OpenVDB's mesh-to-volume
// (tools::meshToLevelSet), so imported shapes go through the same path as the procedural fields,
// and melt like the candle (melted(), geometry/mesh_melt.h: the static grids built here once, the
// melt per t evaluated by shaders/fields/melt.glsl). OpenVDB stays inside mesh_level_set_field.cpp.
#include "geometry/level_set_field.h"
#include "geometry/mesh_melt.h"
#include "geometry/triangle_mesh.h"

#include <memory>

namespace tallow::geometry {

class MeshLevelSetField final : public LevelSetField {
 public:
  /// Voxel size = largest extent of mesh.bounds() / resolution; the band is bandVoxels voxels on
  /// each side of the surface. Holes (loops of edges used by one triangle, as in a scan) are
  /// first closed with a fan around each loop's centroid, since OpenVDB finds the inside by
  /// flood fill from the outside, which leaks through holes. Throws std::invalid_argument for an
  /// empty mesh, resolution < 8 or bandVoxels < 3.
  explicit MeshLevelSetField(const TriangleMesh& mesh, int resolution = 128, double bandVoxels = 3.0);
  ~MeshLevelSetField() override;
  MeshLevelSetField(const MeshLevelSetField&);
  MeshLevelSetField& operator=(const MeshLevelSetField&);

  /// The shape melted to time t (seconds), see geometry/mesh_melt.h: it slumps about its base (the
  /// height shrinks by slump·f while x and z widen by 1/√(1 − slump·f), keeping the volume), a
  /// puddle spreads from its footprint, and it rounds as mean-curvature flow would after f·N steps.
  /// value() evaluates shaders/fields/melt.glsl in double over meltGrids(params), which are built
  /// at the first call and shared by every copy of this field; bounds() is meltBounds. At t ≤ 0 it
  /// is this field. Throws std::invalid_argument on bad params or a non-finite t.
  MeshLevelSetField melted(double t, const MeltParams& params) const;
  /// The static grids of this field's melt (OpenVDB's LevelSetFilter levels as NanoVDB grids):
  /// built once per smoothing count, then shared by every copy and melted() field.
  std::shared_ptr<const MeltGrids> meltGrids(const MeltParams& params) const;
  /// The melt at t as the GPU fill takes it (the shared grids and the scalars at t).
  MeltAt meltAt(double t, const MeltParams& params) const;

  /// The unmelted level set, or the melt at t for a melted() field (melt.glsl in double).
  double value(glm::dvec3 p) const override;
  Aabb bounds() const override;

  struct MeltCache;  ///< the grids per smoothing count, in mesh_level_set_field.cpp

 private:
  MeshLevelSetField(std::shared_ptr<const detail::LevelSetGrid> grid, double voxelSize, double bandVoxels);

  double bandVoxels_;
  std::shared_ptr<MeltCache> meltCache_;      ///< shared by copies, so the grids are built once
  std::shared_ptr<const MeltGrids> melt_;     ///< set on melted() fields with f > 0
  MeltState meltState_;
};

/// OpenVDB's own trilinear sample (tools::BoxSampler) of smoothing level `level` of `grids` at world
/// point p: a second implementation of meltLevelSample, for the tests.
double meltLevelSampleByOpenVdb(const MeltGrids& grids, int level, glm::dvec3 p);

}  // namespace tallow::geometry
