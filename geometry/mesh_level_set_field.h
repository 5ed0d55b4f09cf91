#pragma once
// Any triangle mesh as a narrow-band level set (issue 4, point 1): OpenVDB's mesh-to-volume
// (tools::meshToLevelSet), so imported shapes go through the same path as the procedural fields,
// and melt like the candle (melted()). OpenVDB stays inside mesh_level_set_field.cpp.
#include "geometry/level_set_field.h"
#include "geometry/triangle_mesh.h"

namespace tallow::geometry {

/// How a mesh field melts over its animation, as fractions of the shape at t = 0. Every state is
/// built from the unmelted level set by closed-form steps in the melt fraction f = t / durationS
/// (clamped to [0, 1]), so the same t gives the same field whether the animation plays or jumps.
struct MeltParams {
  double durationS = 20.0;      ///< seconds until fully melted
  double slump = 0.4;           ///< fraction of the height lost by slumping at f = 1, in [0, 0.9]
  double puddleSpread = 0.6;    ///< puddle radius at f = 1, beyond the footprint, × footprint radius
  double puddleHeight = 0.06;   ///< puddle thickness at f = 1 × height
  int smoothingIterations = 12; ///< mean-curvature flow steps at f = 1 (rounds ears, tips and edges)

  bool operator==(const MeltParams&) const = default;
};

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

  /// The shape melted to time t (seconds): it slumps about its base (the height shrinks by
  /// slump·f while x and z widen by 1/√(1 − slump·f), keeping the volume), a puddle spreads from its
  /// footprint, and mean-curvature flow rounds it, with OpenVDB's resampling (resampleToMatch, which
  /// rebuilds the signed distance), CSG union and LevelSetFilter. At t ≤ 0 it is this field. The
  /// last result is cached, so asking for the same t again is cheap. Throws std::invalid_argument
  /// on bad params or a non-finite t.
  MeshLevelSetField melted(double t, const MeltParams& params) const;

 private:
  MeshLevelSetField(std::shared_ptr<const detail::LevelSetGrid> grid, double voxelSize, double bandVoxels);

  double bandVoxels_;
};

}  // namespace tallow::geometry
