#include "geometry/mesh_level_set_field.h"

#include "geometry/openvdb_support.h"

#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>
#include <openvdb/tools/LevelSetFilter.h>
#include <openvdb/tools/MeshToVolume.h>
#include <nanovdb/util/OpenToNanoVDB.h>

#include <algorithm>
#include <cmath>
#include <cstring>
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

/// Largest |difference| of face-neighbouring values of `grid`, in voxels (MeltGrids::maxSlope).
double maxNeighbourSlope(const openvdb::FloatGrid& grid, double voxelSize) {
  const auto accessor = grid.getConstAccessor();
  double slope = 0.0;
  for (auto v = grid.cbeginValueOn(); v; ++v) {
    const openvdb::Coord c = v.getCoord();
    for (int axis = 0; axis < 3; ++axis)
      for (int step : {-1, 1}) {  // both sides: an active voxel may border an inactive tile either way
        openvdb::Coord next = c;
        next[axis] += step;
        slope = std::max(slope, static_cast<double>(std::abs(accessor.getValue(next) - *v)));
      }
  }
  return slope / voxelSize;
}

/// The static part of `base`'s melt (see MeltGrids): the anchor and extents as the CSG melt of
/// issue 4 measured them, then the smoothing levels, each converted to NanoVDB (openToNanoVDB) and
/// appended to one buffer at its own byte address.
std::shared_ptr<const MeltGrids> buildMeltGrids(const openvdb::FloatGrid& base, int iterations, double voxelSize) {
  auto out = std::make_shared<MeltGrids>();
  MeltGrids& g = *out;
  const Aabb box = activeVoxelBounds(base);
  // The band pads the active box by its half-width on every side; the shape sits inside that.
  const double band = base.background();
  const glm::dvec3 lo = glm::dvec3(box.min) + band, hi = glm::dvec3(box.max) - band;
  g.anchor = glm::dvec3(0.5 * (lo.x + hi.x), lo.y, 0.5 * (lo.z + hi.z));  // bottom centre
  g.height = std::max(hi.y - lo.y, voxelSize);
  g.footprint = 0.5 * std::max(hi.x - lo.x, hi.z - lo.z);
  g.voxelSize = voxelSize;
  g.bandWidth = band;
  g.smoothingIterations = iterations;

  const int segments = std::min(iterations, MeltGrids::kMaxSmoothingSegments);
  openvdb::FloatGrid::Ptr current = base.deepCopy();
  int done = 0;
  for (int k = 0; k <= segments; ++k) {
    const int target = segments == 0 ? 0 : static_cast<int>(std::lround(static_cast<double>(iterations) * k / segments));
    if (target > done) {
      openvdb::tools::LevelSetFilter<openvdb::FloatGrid> filter(*current);
      for (; done < target; ++done) filter.meanCurvature();
    }
    auto level = std::make_shared<detail::LevelSetGrid>();
    level->grid = current->deepCopy();
    // melt.glsl takes every level's outside for `band` beyond their active voxels.
    if (static_cast<double>(level->grid->background()) != band)
      throw std::logic_error("MeshLevelSetField: a smoothing level changed the background value");
    g.levels.push_back(level);
    g.iterations.push_back(target);
    const Aabb levelBox = activeVoxelBounds(*level->grid);
    g.levelBounds.extend(levelBox.min);
    g.levelBounds.extend(levelBox.max);
    g.maxSlope = std::max(g.maxSlope, maxNeighbourSlope(*level->grid, voxelSize));

    const auto handle = nanovdb::openToNanoVDB(*level->grid);
    const std::size_t address = g.nanoVdb.size() * sizeof(std::uint32_t);
    // NanoVDB grids are 32-byte aligned and sized; GLSL addresses them with 32 bits.
    if (handle.size() % NANOVDB_DATA_ALIGNMENT != 0 || address + handle.size() > (std::size_t{1} << 31))
      throw std::runtime_error("MeshLevelSetField: the melt's NanoVDB grids exceed 2 GiB");
    g.gridAddress.push_back(static_cast<std::uint32_t>(address));
    g.nanoVdb.resize(g.nanoVdb.size() + handle.size() / sizeof(std::uint32_t));
    std::memcpy(reinterpret_cast<unsigned char*>(g.nanoVdb.data()) + address, handle.data(), handle.size());
  }
  return out;
}

}  // namespace

MeshLevelSetField::MeshLevelSetField(const TriangleMesh& mesh, int resolution, double bandVoxels)
    : MeshLevelSetField(meshToGrid(mesh, checkedVoxelSize(mesh, resolution, bandVoxels), bandVoxels),
                        checkedVoxelSize(mesh, resolution, bandVoxels), bandVoxels) {}

MeshLevelSetField::MeshLevelSetField(std::shared_ptr<const detail::LevelSetGrid> grid, double voxelSize, double bandVoxels)
    : LevelSetField(std::move(grid), voxelSize, bandVoxels * voxelSize),
      bandVoxels_(bandVoxels),
      meltCache_(std::make_shared<MeltCache>()) {}

MeshLevelSetField::~MeshLevelSetField() = default;
MeshLevelSetField::MeshLevelSetField(const MeshLevelSetField&) = default;
MeshLevelSetField& MeshLevelSetField::operator=(const MeshLevelSetField&) = default;

struct MeshLevelSetField::MeltCache {
  std::mutex mutex;
  std::map<int, std::shared_ptr<const MeltGrids>> bySmoothing;  ///< smoothing count → grids
};

std::shared_ptr<const MeltGrids> MeshLevelSetField::meltGrids(const MeltParams& params) const {
  checkMeltParams(params, 0.0);
  const std::lock_guard lock(meltCache_->mutex);
  std::shared_ptr<const MeltGrids>& grids = meltCache_->bySmoothing[params.smoothingIterations];
  if (!grids) grids = buildMeltGrids(*levelSet()->grid, params.smoothingIterations, voxelSize());
  return grids;
}

MeltAt MeshLevelSetField::meltAt(double t, const MeltParams& params) const {
  checkMeltParams(params, t);
  MeltAt at;
  at.grids = meltGrids(params);
  at.state = meltStateAt(*at.grids, t, params);
  return at;
}

MeshLevelSetField MeshLevelSetField::melted(double t, const MeltParams& params) const {
  checkMeltParams(params, t);
  if (std::clamp(t / params.durationS, 0.0, 1.0) == 0.0) return *this;
  const MeltAt at = meltAt(t, params);
  MeshLevelSetField out(*this);
  out.melt_ = at.grids;
  out.meltState_ = at.state;
  return out;
}

double MeshLevelSetField::value(glm::dvec3 p) const {
  return melt_ ? meltValue(*melt_, meltState_, p) : LevelSetField::value(p);
}

Aabb MeshLevelSetField::bounds() const { return melt_ ? meltBounds(*melt_, meltState_) : LevelSetField::bounds(); }

double meltLevelSampleByOpenVdb(const MeltGrids& grids, int level, glm::dvec3 p) {
  const openvdb::FloatGrid& grid = *grids.levels.at(static_cast<std::size_t>(level))->grid;
  const openvdb::Vec3d ijk = grid.worldToIndex(openvdb::Vec3d(p.x, p.y, p.z));
  return static_cast<double>(openvdb::tools::BoxSampler::sample(grid.getConstUnsafeAccessor(), ijk));
}

}  // namespace tallow::geometry
