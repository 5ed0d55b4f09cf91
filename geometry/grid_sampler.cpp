#include "geometry/grid_sampler.h"

#include <algorithm>
#include <stdexcept>
#include <thread>

namespace tallow::geometry {

namespace {
/// The lattice has one padding cell on each side of the box: (n − 1) cells span side + 2 cells.
constexpr int kPaddingCells = 1;
constexpr int kMinSamples = 2 * kPaddingCells + 2;
}  // namespace

SampledLattice latticeOver(const Aabb& box, int n) {
  if (n < kMinSamples) throw std::invalid_argument("sampleField: need at least 4 samples per axis");
  if (box.empty()) throw std::invalid_argument("sampleField: empty box");
  const glm::dvec3 size(box.size());
  const double side = std::max({size.x, size.y, size.z});
  if (!(side > 0.0)) throw std::invalid_argument("sampleField: box has zero size");

  SampledLattice lattice;
  lattice.n = n;
  lattice.cellSize = side / static_cast<double>(n - 1 - 2 * kPaddingCells);
  lattice.origin = glm::dvec3(box.centre()) - glm::dvec3(0.5 * side + kPaddingCells * lattice.cellSize);
  return lattice;
}

SampledLattice sampleField(const ScalarField& field, const Aabb& box, int n) {
  SampledLattice lattice = latticeOver(box, n);
  lattice.values.resize(static_cast<std::size_t>(n) * static_cast<std::size_t>(n) * static_cast<std::size_t>(n));

  const unsigned threads = std::clamp(std::thread::hardware_concurrency(), 1u, static_cast<unsigned>(n));
  auto work = [&](unsigned first) {
    for (int z = static_cast<int>(first); z < n; z += static_cast<int>(threads))
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
          lattice.values[lattice.index(x, y, z)] = static_cast<float>(field.value(lattice.position(x, y, z)));
  };
  {
    std::vector<std::jthread> pool;  // joined at the end of this block, before lattice is returned
    pool.reserve(threads - 1);
    for (unsigned i = 1; i < threads; ++i) pool.emplace_back(work, i);
    work(0);
  }
  return lattice;
}

SampledLattice sampleField(const ScalarField& field, int n) { return sampleField(field, field.bounds(), n); }

}  // namespace tallow::geometry
