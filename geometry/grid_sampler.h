#pragma once
// Samples a ScalarField on a cubic lattice: the layout the GPU upload (3D texture) and the CPU
// reference mesher share, so both contour exactly the same numbers.
#include "geometry/scalar_field.h"

#include <cstddef>
#include <vector>

namespace tallow::geometry {

/// n³ samples of a field; sample (x, y, z) sits at origin + cellSize·(x, y, z), world units.
struct SampledLattice {
  int n = 0;                ///< samples per axis
  double cellSize = 0.0;    ///< metres between neighbouring samples (same on every axis)
  glm::dvec3 origin{0.0};   ///< world position of sample (0, 0, 0)
  std::vector<float> values;  ///< n³ values, x fastest: index = x + n·(y + n·z)

  std::size_t index(int x, int y, int z) const {
    const auto un = static_cast<std::size_t>(n);
    return static_cast<std::size_t>(x) + un * (static_cast<std::size_t>(y) + un * static_cast<std::size_t>(z));
  }
  float at(int x, int y, int z) const { return values[index(x, y, z)]; }
  glm::dvec3 position(int x, int y, int z) const { return origin + cellSize * glm::dvec3(x, y, z); }
};

/// The lattice sampleField(field, box, n) fills, without its values (n, origin, cell size): what
/// a field evaluated on the GPU (GpuBlobField) is filled over.
SampledLattice latticeOver(const Aabb& box, int n);
/// Samples `field` on n³ points (n ≥ 4) covering the cube around `box` (side = its largest
/// extent, same centre) padded by one cell on every side, so that a surface inside `box` never
/// touches the outermost samples. Runs on all hardware threads (std::thread, split along z).
SampledLattice sampleField(const ScalarField& field, const Aabb& box, int n);
/// The same over field.bounds().
SampledLattice sampleField(const ScalarField& field, int n);

}  // namespace tallow::geometry
