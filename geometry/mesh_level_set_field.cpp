#include "geometry/mesh_level_set_field.h"

#include "geometry/openvdb_support.h"

#include <openvdb/openvdb.h>
#include <openvdb/tools/Composite.h>
#include <openvdb/tools/GridTransformer.h>
#include <openvdb/tools/LevelSetFilter.h>
#include <openvdb/tools/MeshToVolume.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <stdexcept>
#include <vector>

namespace tallow::geometry {

namespace {

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


/// Checks the mesh and the band, then returns the voxel size (largest extent / resolution).
double checkedVoxelSize(const TriangleMesh& mesh, int resolution, double bandVoxels) {
  const double voxelSize = resolution > 0 ? largestExtent(mesh) / resolution : 0.0;
  if (mesh.triangles.empty() || !(voxelSize > 0.0) || resolution < 8 || !(bandVoxels >= 3.0))
    throw std::invalid_argument("MeshLevelSetField: need a non-empty mesh, resolution >= 8, bandVoxels >= 3");
  return voxelSize;
}

std::shared_ptr<const detail::LevelSetGrid> meshToGrid(const TriangleMesh& mesh, double voxelSize, double bandVoxels) {
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
  const auto xform = openvdb::math::Transform::createLinearTransform(voxelSize);
  auto grid = std::make_shared<detail::LevelSetGrid>();
  grid->grid = openvdb::tools::meshToLevelSet<openvdb::FloatGrid>(*xform, points, triangles, static_cast<float>(bandVoxels));
  return grid;
}

/// The melt at fraction f of `base` (see MeshLevelSetField::melted), from scratch.
std::shared_ptr<const detail::LevelSetGrid> melt(const openvdb::FloatGrid& base, double f, const MeltParams& p,
                                                 double voxelSize) {
  const Aabb box = activeVoxelBounds(base);
  // The band pads the active box by its half-width on every side; the shape sits inside that.
  const double band = base.background();
  const openvdb::Vec3d lo(box.min.x + band, box.min.y + band, box.min.z + band);
  const openvdb::Vec3d hi(box.max.x - band, box.max.y - band, box.max.z - band);
  const openvdb::Vec3d anchor(0.5 * (lo.x() + hi.x()), lo.y(), 0.5 * (lo.z() + hi.z()));  // bottom centre
  const double height = std::max(hi.y() - lo.y(), voxelSize);
  const double footprint = 0.5 * std::max(hi.x() - lo.x(), hi.z() - lo.z());

  // 1. Slump about the bottom centre, volume-preserving: y × s, x and z × 1/√s. The source grid
  //    gets the deformed transform (sharing its tree); resampleToMatch rebuilds a signed distance
  //    on the original voxel lattice.
  const double s = 1.0 - p.slump * f;
  openvdb::FloatGrid::Ptr slumped;
  if (s < 1.0) {
    // A shallow copy: the tree is shared (and only read), the transform pointer is the copy's own.
    openvdb::FloatGrid::Ptr deformed = openvdb::ConstPtrCast<openvdb::FloatGrid>(base.copy());
    openvdb::math::Transform::Ptr xform = base.transform().copy();
    xform->postTranslate(-anchor);
    xform->postScale(openvdb::Vec3d(1.0 / std::sqrt(s), s, 1.0 / std::sqrt(s)));
    xform->postTranslate(anchor);
    deformed->setTransform(xform);
    slumped = openvdb::FloatGrid::create(base.background());
    slumped->setTransform(base.transform().copy());
    slumped->setGridClass(openvdb::GRID_LEVEL_SET);
    openvdb::tools::resampleToMatch<openvdb::tools::BoxSampler>(*deformed, *slumped);
  } else {
    slumped = base.deepCopy();
  }

  // 2. The puddle: a disc at the base, wider and thicker as f grows, welded on by CSG union.
  const double puddleHeight = p.puddleHeight * height * f;
  if (puddleHeight > voxelSize) {
    const double radius = footprint / std::sqrt(s) * (1.0 + p.puddleSpread * f);
    auto puddle = cylinderLevelSet(radius, anchor.y(), anchor.y() + puddleHeight, slumped->transform(), anchor.x(),
                                   anchor.z());
    openvdb::tools::csgUnion(*slumped, *puddle);
  }

  // 3. Mean-curvature flow rounds ears, tips and edges, and blends the puddle into the body.
  const int iterations = static_cast<int>(std::lround(p.smoothingIterations * f));
  if (iterations > 0) {
    openvdb::tools::LevelSetFilter<openvdb::FloatGrid> filter(*slumped);
    for (int k = 0; k < iterations; ++k) filter.meanCurvature();
  }
  auto out = std::make_shared<detail::LevelSetGrid>();
  out->grid = slumped;
  return out;
}

}  // namespace

MeshLevelSetField::MeshLevelSetField(const TriangleMesh& mesh, int resolution, double bandVoxels)
    : MeshLevelSetField(meshToGrid(mesh, checkedVoxelSize(mesh, resolution, bandVoxels), bandVoxels),
                        checkedVoxelSize(mesh, resolution, bandVoxels), bandVoxels) {}

MeshLevelSetField::MeshLevelSetField(std::shared_ptr<const detail::LevelSetGrid> grid, double voxelSize, double bandVoxels)
    : LevelSetField(std::move(grid), voxelSize, bandVoxels * voxelSize), bandVoxels_(bandVoxels) {}

MeshLevelSetField::~MeshLevelSetField() = default;
MeshLevelSetField::MeshLevelSetField(const MeshLevelSetField&) = default;
MeshLevelSetField& MeshLevelSetField::operator=(const MeshLevelSetField&) = default;

MeshLevelSetField MeshLevelSetField::melted(double t, const MeltParams& params) const {
  const MeltParams& p = params;
  if (!(p.durationS > 0.0) || !(p.slump >= 0.0 && p.slump <= 0.9) || !(p.puddleSpread >= 0.0) ||
      !(p.puddleHeight >= 0.0 && p.puddleHeight <= 1.0) || p.smoothingIterations < 0 || p.smoothingIterations > 200 ||
      !std::isfinite(t))
    throw std::invalid_argument("MeltParams: durationS > 0, slump in [0, 0.9], puddleSpread >= 0, puddleHeight in [0, 1], "
                                "smoothingIterations in [0, 200], t finite");
  const double f = std::clamp(t / p.durationS, 0.0, 1.0);
  if (f == 0.0) return *this;
  // The last melt of any field, so re-asking the same (field, f, params) is cheap.
  static std::mutex mutex;
  static std::shared_ptr<const detail::LevelSetGrid> lastBase;  // held, so its address is not reused
  static double lastF = -1.0;
  static MeltParams lastParams;
  static std::shared_ptr<const detail::LevelSetGrid> last;
  const std::lock_guard lock(mutex);
  if (!last || lastBase != levelSet() || lastF != f || !(lastParams == p)) {
    last = melt(*levelSet()->grid, f, p, voxelSize());
    lastBase = levelSet();
    lastF = f;
    lastParams = p;
  }
  return MeshLevelSetField(last, voxelSize(), bandVoxels_);
}

}  // namespace tallow::geometry
