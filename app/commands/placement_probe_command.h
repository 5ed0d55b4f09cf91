#pragma once
// `tallow probe placement`: dual contouring's two vertex placements (field.placement = mass | qef)
// against the exact surface (issue 16, point 4). For each shape — sharp: a rotated cube (an exact
// signed distance) and the candle at t = 0, before its rim melts (its wick left out: thinner than a
// cell); smooth: a sphere and the blob — and each lattice resolution, the GPU extraction with each
// placement is measured against the shape's exact surface: the largest and mean distance from the
// mesh to the surface and from the surface to the mesh (in cells of the lattice), the symmetric
// Hausdorff distance, the mesh checks (edges not in exactly two triangles, zero-area triangles,
// winding against the gradient) and the extraction's GPU time. Writes JSON.
#include <string>
#include <vector>

namespace tallow::app {

struct ProbePlacementOptions {
  std::vector<std::string> shapes{"cube", "candle", "sphere", "blob"};
  std::vector<int> resolutions{32, 64, 128};
  int repeats = 3;  ///< timed extractions per placement after one warm-up; the median is reported
  std::string gl = "osmesa";
  std::string out;  ///< JSON file
};

int runProbePlacement(const ProbePlacementOptions& options);

}  // namespace tallow::app
