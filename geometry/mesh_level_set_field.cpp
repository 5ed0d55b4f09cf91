#include "geometry/mesh_level_set_field.h"

#include "geometry/openvdb_bounds.h"

#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>
#include <openvdb/tools/MeshToVolume.h>

#include <algorithm>
#include <map>
#include <mutex>
#include <stdexcept>
#include <vector>

namespace tallow::geometry {

struct detail::MeshLevelSetGrid {
  openvdb::FloatGrid::Ptr grid;
};

namespace {

void initialiseOpenVdb() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

double largestExtent(const TriangleMesh& mesh) {
  const Aabb box = mesh.bounds();
  if (box.empty()) return 0.0;
  const glm::vec3 size = box.size();
  return static_cast<double>(std::max({size.x, size.y, size.z}));
}

/// Closes every hole of a scan (a loop of edges used by one triangle) with a fan around the loop's
/// centroid, wound like its neighbours. OpenVDB's mesh-to-level-set decides inside from the
/// outside by flood fill, which leaks through any hole and leaves no inside at all.
void closeHoles(std::vector<openvdb::Vec3s>& points, std::vector<openvdb::Vec3I>& triangles) {
  std::map<std::pair<unsigned, unsigned>, int> uses;  // undirected edge → triangles using it
  for (const auto& t : triangles)
    for (int i = 0; i < 3; ++i) ++uses[std::minmax(t[i], t[(i + 1) % 3])];
  std::multimap<unsigned, unsigned> next;  // boundary edges a → b as the triangles run them
  for (const auto& t : triangles)
    for (int i = 0; i < 3; ++i)
      if (uses[std::minmax(t[i], t[(i + 1) % 3])] == 1) next.emplace(t[i], t[(i + 1) % 3]);
  while (!next.empty()) {
    std::vector<unsigned> loop;
    auto it = next.begin();
    const unsigned first = it->first;
    unsigned at = first;
    while (it != next.end()) {
      loop.push_back(at);
      at = it->second;
      next.erase(it);
      if (at == first) break;
      it = next.find(at);
    }
    if (at != first || loop.size() < 3) continue;  // not a closed loop: leave it
    openvdb::Vec3d centre(0.0);
    for (unsigned v : loop) centre += openvdb::Vec3d(points[v]);
    centre /= static_cast<double>(loop.size());
    const auto c = static_cast<unsigned>(points.size());
    points.emplace_back(static_cast<float>(centre.x()), static_cast<float>(centre.y()), static_cast<float>(centre.z()));
    // The neighbours run a → b along the boundary, so the cap runs b → a.
    for (std::size_t i = 0; i < loop.size(); ++i) triangles.emplace_back(loop[(i + 1) % loop.size()], loop[i], c);
  }
}

}  // namespace

MeshLevelSetField::MeshLevelSetField(const TriangleMesh& mesh, int resolution, double bandVoxels)
    : voxelSize_(resolution > 0 ? largestExtent(mesh) / resolution : 0.0), bandVoxels_(bandVoxels) {
  if (mesh.triangles.empty() || !(voxelSize_ > 0.0) || resolution < 8 || !(bandVoxels >= 3.0))
    throw std::invalid_argument("MeshLevelSetField: need a non-empty mesh, resolution >= 8, bandVoxels >= 3");
  initialiseOpenVdb();
  std::vector<openvdb::Vec3s> points;
  points.reserve(mesh.positions.size());
  for (const glm::vec3& p : mesh.positions) points.emplace_back(p.x, p.y, p.z);
  std::vector<openvdb::Vec3I> triangles;
  triangles.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    if (t[0] >= points.size() || t[1] >= points.size() || t[2] >= points.size())
      throw std::invalid_argument("MeshLevelSetField: triangle index out of range");
    triangles.emplace_back(t[0], t[1], t[2]);
  }
  closeHoles(points, triangles);
  const auto xform = openvdb::math::Transform::createLinearTransform(voxelSize_);
  auto grid = std::make_shared<detail::MeshLevelSetGrid>();
  grid->grid = openvdb::tools::meshToLevelSet<openvdb::FloatGrid>(*xform, points, triangles,
                                                                  static_cast<float>(bandVoxels_));
  grid_ = std::move(grid);
}

MeshLevelSetField::~MeshLevelSetField() = default;
MeshLevelSetField::MeshLevelSetField(const MeshLevelSetField&) = default;
MeshLevelSetField& MeshLevelSetField::operator=(const MeshLevelSetField&) = default;

double MeshLevelSetField::value(glm::dvec3 p) const {
  const openvdb::FloatGrid& grid = *grid_->grid;
  const openvdb::Vec3d ijk = grid.worldToIndex(openvdb::Vec3d(p.x, p.y, p.z));
  // An unsafe (unregistered) accessor per call: value() runs on many threads at once.
  const auto accessor = grid.getConstUnsafeAccessor();
  return static_cast<double>(openvdb::tools::BoxSampler::sample(accessor, ijk));
}

glm::dvec3 MeshLevelSetField::gradient(glm::dvec3 p) const {
  return centralDifferenceGradient(p, 0.5 * voxelSize_);
}

Aabb MeshLevelSetField::bounds() const { return activeVoxelBounds(*grid_->grid); }

}  // namespace tallow::geometry
