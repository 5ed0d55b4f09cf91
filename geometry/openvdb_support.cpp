#include "geometry/openvdb_support.h"

#include <openvdb/tools/LevelSetSphere.h>
#include <openvdb/tools/MeshToVolume.h>

#include <cmath>
#include <mutex>
#include <numbers>
#include <vector>

namespace tallow::geometry {

void initialiseOpenVdb() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

Aabb activeVoxelBounds(const openvdb::FloatGrid& grid) {
  const openvdb::CoordBBox box = grid.evalActiveVoxelBoundingBox();
  const openvdb::Vec3d lo = grid.indexToWorld(box.min().asVec3d()), hi = grid.indexToWorld(box.max().asVec3d());
  Aabb out;
  out.extend(glm::vec3(static_cast<float>(lo.x()), static_cast<float>(lo.y()), static_cast<float>(lo.z())));
  out.extend(glm::vec3(static_cast<float>(hi.x()), static_cast<float>(hi.y()), static_cast<float>(hi.z())));
  return out;
}

openvdb::FloatGrid::Ptr cylinderLevelSet(double radius, double y0, double y1, const openvdb::math::Transform& xform,
                                         double centreX, double centreZ) {
  constexpr unsigned n = 96;
  std::vector<openvdb::Vec3s> points;
  std::vector<openvdb::Vec3I> triangles;
  for (unsigned i = 0; i < n; ++i) {
    const double a = 2.0 * std::numbers::pi * i / n;
    const auto x = static_cast<float>(centreX + radius * std::cos(a)), z = static_cast<float>(centreZ + radius * std::sin(a));
    points.emplace_back(x, static_cast<float>(y0), z);
    points.emplace_back(x, static_cast<float>(y1), z);
  }
  const unsigned bottom = 2 * n, top = 2 * n + 1;
  points.emplace_back(static_cast<float>(centreX), static_cast<float>(y0), static_cast<float>(centreZ));
  points.emplace_back(static_cast<float>(centreX), static_cast<float>(y1), static_cast<float>(centreZ));
  for (unsigned i = 0; i < n; ++i) {
    const unsigned j = (i + 1) % n;
    const unsigned b0 = 2 * i, t0 = 2 * i + 1, b1 = 2 * j, t1 = 2 * j + 1;
    triangles.emplace_back(b0, t0, t1);
    triangles.emplace_back(b0, t1, b1);
    triangles.emplace_back(bottom, b0, b1);
    triangles.emplace_back(top, t1, t0);
  }
  return openvdb::tools::meshToLevelSet<openvdb::FloatGrid>(xform, points, triangles, kHalfWidthVoxels);
}

openvdb::FloatGrid::Ptr sphereLevelSet(double radius, glm::dvec3 centre, double voxelSize) {
  return openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(
      static_cast<float>(radius), openvdb::Vec3f(static_cast<float>(centre.x), static_cast<float>(centre.y),
                                                  static_cast<float>(centre.z)),
      static_cast<float>(voxelSize), kHalfWidthVoxels);
}

}  // namespace tallow::geometry
