#pragma once
// `tallow probe cost`: evaluations per second of each BSSRDF model on the CPU (float and double,
// one thread) and through the GLSL compute path, and the float-against-double error distribution,
// on one fixed set of random configurations. Writes JSON; timings are medians of repeated runs.
#include <cstdint>
#include <string>

namespace tallow::app {

struct ProbeCostOptions {
  std::uint64_t count = 200000;  ///< configurations per model (photon beam diffusion uses count/10)
  int repeats = 5;
  bool gpu = true;
  std::string gl = "osmesa";
  std::string out;  ///< JSON file
};

int runProbeCost(const ProbeCostOptions& options);

}  // namespace tallow::app
