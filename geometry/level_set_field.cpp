#include "geometry/level_set_field.h"

#include "geometry/openvdb_support.h"

#include <openvdb/tools/Interpolation.h>

#include <stdexcept>
#include <utility>

namespace tallow::geometry {

LevelSetField::LevelSetField(std::shared_ptr<const detail::LevelSetGrid> grid, double voxelSize, double bandWidth)
    : grid_(std::move(grid)), voxelSize_(voxelSize), bandWidth_(bandWidth) {
  if (!grid_ || !grid_->grid) throw std::logic_error("LevelSetField: no grid");
}
LevelSetField::~LevelSetField() = default;
LevelSetField::LevelSetField(const LevelSetField&) = default;
LevelSetField& LevelSetField::operator=(const LevelSetField&) = default;

double LevelSetField::value(glm::dvec3 p) const {
  const openvdb::FloatGrid& grid = *grid_->grid;
  const openvdb::Vec3d ijk = grid.worldToIndex(openvdb::Vec3d(p.x, p.y, p.z));
  // An unsafe (unregistered) accessor per call: value() runs on many threads at once.
  const auto accessor = grid.getConstUnsafeAccessor();
  return static_cast<double>(openvdb::tools::BoxSampler::sample(accessor, ijk));
}

glm::dvec3 LevelSetField::gradient(glm::dvec3 p) const { return centralDifferenceGradient(p, 0.5 * voxelSize_); }

Aabb LevelSetField::bounds() const { return activeVoxelBounds(*grid_->grid); }

}  // namespace tallow::geometry
