#pragma once
// Distances from points to a triangle mesh: the closest point of one triangle, and a uniform bucket
// grid of a mesh's triangles for nearest-surface queries (Hausdorff distances of the geometry tests
// and of `tallow probe placement`).
#include <glm/glm.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "geometry/triangle_mesh.h"

namespace tallow::geometry {

/// Distance from p to the closed triangle abc (closest point by Voronoi regions, after Ericson,
/// Real-Time Collision Detection §5.1.5); degenerate triangles fall out as segments or points.
double pointTriangleDistance(glm::dvec3 p, glm::dvec3 a, glm::dvec3 b, glm::dvec3 c);

/// A mesh's triangles bucketed in a uniform grid of cubic cells (each triangle in every cell its
/// bounding box overlaps), for nearest-surface queries: distance() searches shells of cells around
/// the query point and stops once no unsearched cell can hold anything closer.
class TriangleGrid {
 public:
  /// `bucketSize` > 0 in world units; about the triangles' size is best (e.g. the lattice cell).
  TriangleGrid(const TriangleMesh& mesh, double bucketSize);

  /// Distance from p to the nearest triangle, or `cap` when none is closer than cap.
  double distance(glm::dvec3 p, double cap) const;

 private:
  glm::ivec3 cellOf(glm::dvec3 p) const {
    const glm::ivec3 c(glm::floor((p - origin_) / bucket_));
    return glm::clamp(c, glm::ivec3(0), glm::ivec3(dims_[0], dims_[1], dims_[2]) - 1);
  }
  std::size_t cellCount() const {
    return static_cast<std::size_t>(dims_[0]) * static_cast<std::size_t>(dims_[1]) * static_cast<std::size_t>(dims_[2]);
  }
  std::size_t flat(int x, int y, int z) const {
    return static_cast<std::size_t>(x) +
           static_cast<std::size_t>(dims_[0]) * (static_cast<std::size_t>(y) + static_cast<std::size_t>(dims_[1]) * static_cast<std::size_t>(z));
  }

  const TriangleMesh& mesh_;
  double bucket_;
  glm::dvec3 origin_{0.0};
  std::array<int, 3> dims_{1, 1, 1};
  std::vector<std::uint32_t> start_, items_;  ///< CSR: triangles of cell i are items_[start_[i] .. start_[i + 1])
};

}  // namespace tallow::geometry
