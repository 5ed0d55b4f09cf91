#pragma once
// How a mesh field melts (issue 4, point 1; on the GPU since issue 16, points 2 and 3). The melt is
// split where the work is: what needs OpenVDB is built once per mesh (MeltGrids: the narrow-band
// level set and a few copies rounded by mean-curvature flow, as NanoVDB grids in one buffer, built
// by MeshLevelSetField::meltGrids), and what changes with t is closed-form per point
// (shaders/fields/melt.glsl): a volume-keeping slump as a domain warp of the grids, the rounding as
// a blend of the two smoothing levels around f·iterations, and a puddle joined by a smooth union.
// The CPU computes a handful of scalars per t (meltStateAt, like the blob's centres); the GPU
// (geometry::GpuMeltField) and the CPU (meltValue, through MeshLevelSetField::melted) then
// evaluate the same lines of melt.glsl over the same NanoVDB bytes, the GPU in float, the CPU in
// double. Why a blend of precomputed levels instead of OpenVDB's filter per frame: the filter is
// iterative on the CPU; a blend of distance fields is a distance bound, and at the levels it is
// exactly the filter's result. No OpenVDB type appears here.
#include "geometry/triangle_mesh.h"

#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace tallow::geometry {

namespace detail {
struct LevelSetGrid;  // the OpenVDB FloatGrid, in geometry/openvdb_support.h
}

/// How a mesh field melts over its animation, as fractions of the shape at t = 0. Every state is
/// a closed-form function of the melt fraction f = t / durationS (clamped to [0, 1]) over grids
/// built once, so the same t gives the same field whether the animation plays or jumps.
struct MeltParams {
  double durationS = 20.0;      ///< seconds until fully melted
  double slump = 0.4;           ///< fraction of the height lost by slumping at f = 1, in [0, 0.9]
  double puddleSpread = 0.6;    ///< puddle radius at f = 1, beyond the footprint, × footprint radius
  double puddleHeight = 0.06;   ///< puddle thickness at f = 1 × height
  int smoothingIterations = 12; ///< mean-curvature flow steps at f = 1 (rounds ears, tips and edges)

  bool operator==(const MeltParams&) const = default;
};

/// Throws std::invalid_argument unless durationS > 0, slump in [0, 0.9], puddleSpread ≥ 0,
/// puddleHeight in [0, 1], smoothingIterations in [0, 200] and t finite.
void checkMeltParams(const MeltParams& params, double t);

/// The static part of a mesh's melt: built once per mesh (and smoothing count), read-only after.
struct MeltGrids {
  /// Smoothing levels at most: level k holds round(k·N / L) mean-curvature steps, L = min(N, this),
  /// so f·N steps are a blend of two levels at most N/L ≤ 4 steps apart (N = 12 by default).
  static constexpr int kMaxSmoothingSegments = 3;

  std::vector<std::uint32_t> nanoVdb;      ///< the levels as NanoVDB float grids, one after another
  std::vector<std::uint32_t> gridAddress;  ///< byte address of level k in nanoVdb
  std::vector<int> iterations;             ///< mean-curvature steps of level k, ascending from 0
  /// The same levels as OpenVDB grids: the second implementation the tests sample
  /// (meltLevelSampleByOpenVdb in mesh_level_set_field.h).
  std::vector<std::shared_ptr<const detail::LevelSetGrid>> levels;
  int smoothingIterations = 0;  ///< the MeltParams::smoothingIterations these grids were built for
  glm::dvec3 anchor{0.0};       ///< bottom centre of the unmelted shape, world units
  double height = 0.0;          ///< height of the unmelted shape
  double footprint = 0.0;       ///< half its larger horizontal extent
  double voxelSize = 0.0;
  double bandWidth = 0.0;       ///< half-width of the narrow band (the background value)
  Aabb levelBounds;             ///< world box of every level's active voxels
  /// Largest |difference| of two face-neighbouring voxel values over every level, in voxels: the
  /// trilinear interpolant's gradient is at most √3 times this (the tests' float error bound).
  double maxSlope = 0.0;

  std::size_t bytes() const { return nanoVdb.size() * sizeof(std::uint32_t); }
  /// Index-space box outside which a trilinear sample of any level reads only background values:
  /// levelBounds / voxelSize grown by kBackgroundMarginVoxels (a sample's corners reach one voxel;
  /// the half voxel covers levelBounds' float rounding).
  static constexpr double kBackgroundMarginVoxels = 1.5;
  glm::dvec3 backgroundBoxLo() const { return glm::dvec3(levelBounds.min) / voxelSize - kBackgroundMarginVoxels; }
  glm::dvec3 backgroundBoxHi() const { return glm::dvec3(levelBounds.max) / voxelSize + kBackgroundMarginVoxels; }
};

/// The per-t scalars of a melt: shaders/fields/melt.glsl's MeltShape, in double.
struct MeltState {
  double f = 0.0;            ///< melt fraction
  double heightScale = 1.0;  ///< s = 1 − slump·f
  std::uint32_t gridA = 0;   ///< byte address of the level below f·N steps
  std::uint32_t gridB = 0;   ///< and above
  double blend = 0.0;        ///< weight of gridB
  double puddleRadius = 0.0;
  double puddleHeight = 0.0;  ///< 0 until the puddle is thicker than a voxel (as the CSG melt had it)
  double joinRadius = 0.0;    ///< smooth-union radius: min(puddle thickness, band · s)
};

/// A melting mesh at one t, as the GPU fill needs it: the shared static grids and the scalars.
struct MeltAt {
  std::shared_ptr<const MeltGrids> grids;
  MeltState state;
};

/// The scalars at time t (seconds): f = t / durationS clamped to [0, 1]. Checks `params` and t
/// (checkMeltParams); throws std::logic_error when `grids` were built for another smoothing count.
MeltState meltStateAt(const MeltGrids& grids, double t, const MeltParams& params);
/// shaders/fields/melt.glsl's meltFieldValue at world point p, in double: negative inside.
double meltValue(const MeltGrids& grids, const MeltState& state, glm::dvec3 p);
/// The same lines' trilinear sample of level `level` at world point p (PNanoVDB over nanoVdb).
double meltLevelSample(const MeltGrids& grids, int level, glm::dvec3 p);
/// World box that contains the melted surface at `state` (value ≥ 0 outside it).
Aabb meltBounds(const MeltGrids& grids, const MeltState& state);

}  // namespace tallow::geometry
