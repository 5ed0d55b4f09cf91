#pragma once
// A ScalarField backed by an OpenVDB narrow-band level set (FloatGrid, metres, value < 0 inside):
// what the melting candle and mesh-derived fields share. OpenVDB stays in the .cpp files.
#include "geometry/scalar_field.h"

#include <memory>

namespace tallow::geometry {

namespace detail {
struct LevelSetGrid;  // the OpenVDB FloatGrid, in geometry/openvdb_support.h
}

class LevelSetField : public ScalarField {
 public:
  ~LevelSetField() override;

  /// Trilinear (box) sample of the level set, metres; outside the narrow band ± the band width.
  double value(glm::dvec3 p) const override;
  /// Central differences of value() with a step of half a voxel.
  glm::dvec3 gradient(glm::dvec3 p) const override;
  /// World box of the active voxels (the narrow band), so it contains the whole surface.
  Aabb bounds() const override;

  double voxelSize() const { return voxelSize_; }
  double bandWidth() const { return bandWidth_; }  ///< half-width of the narrow band, metres

 protected:
  /// `bandWidth`: half-width of the grid's narrow band, metres.
  LevelSetField(std::shared_ptr<const detail::LevelSetGrid> grid, double voxelSize, double bandWidth);
  LevelSetField(const LevelSetField&);
  LevelSetField& operator=(const LevelSetField&);
  const std::shared_ptr<const detail::LevelSetGrid>& levelSet() const { return grid_; }

 private:
  std::shared_ptr<const detail::LevelSetGrid> grid_;
  double voxelSize_;
  double bandWidth_;
};

}  // namespace tallow::geometry
