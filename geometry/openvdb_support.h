#pragma once
// What the OpenVDB-backed fields share. Include only from .cpp files: OpenVDB's headers stay out
// of every other translation unit (the public headers see detail::LevelSetGrid as an incomplete type).
#include <openvdb/openvdb.h>

#include "geometry/triangle_mesh.h"

#include <glm/glm.hpp>

namespace tallow::geometry {

namespace detail {
/// A narrow-band level set (value < 0 inside, metres), shared read-only between field copies.
struct LevelSetGrid {
  openvdb::FloatGrid::Ptr grid;
};
}  // namespace detail

/// openvdb::initialize(), once per process, from any thread.
void initialiseOpenVdb();

/// World bounds of a level-set grid's active voxels.
Aabb activeVoxelBounds(const openvdb::FloatGrid& grid);

/// Half-width of every narrow band we build, in voxels (OpenVDB's default).
constexpr float kHalfWidthVoxels = 3.0f;

/// Level set of a closed cylinder along y, its axis through (centreX, ·, centreZ), from y0 to y1, by
/// OpenVDB's mesh-to-level-set on a 96-sided prism (OpenVDB 10 has no cylinder primitive; the chord
/// error R·(1 − cos(π/96)) is 10 µm at R = 2 cm).
openvdb::FloatGrid::Ptr cylinderLevelSet(double radius, double y0, double y1, const openvdb::math::Transform& xform,
                                         double centreX = 0.0, double centreZ = 0.0);

/// Level set of a sphere (OpenVDB's createLevelSetSphere).
openvdb::FloatGrid::Ptr sphereLevelSet(double radius, glm::dvec3 centre, double voxelSize);

}  // namespace tallow::geometry
