#pragma once
// World bounds of a level-set grid's active voxels. Include only from .cpp files that already
// include OpenVDB (its headers stay out of every other translation unit).
#include <openvdb/openvdb.h>

#include "geometry/triangle_mesh.h"

namespace tallow::geometry {

inline Aabb activeVoxelBounds(const openvdb::FloatGrid& grid) {
  const openvdb::CoordBBox box = grid.evalActiveVoxelBoundingBox();
  const openvdb::Vec3d lo = grid.indexToWorld(box.min().asVec3d()), hi = grid.indexToWorld(box.max().asVec3d());
  Aabb out;
  out.extend(glm::vec3(static_cast<float>(lo.x()), static_cast<float>(lo.y()), static_cast<float>(lo.z())));
  out.extend(glm::vec3(static_cast<float>(hi.x()), static_cast<float>(hi.y()), static_cast<float>(hi.z())));
  return out;
}

}  // namespace tallow::geometry
