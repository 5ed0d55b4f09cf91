#pragma once
// `tallow probe extraction`: the benchmark of issue 4, point 8. For each field (blob, candle) and
// lattice resolution: CPU sampling time, GPU surface-nets extraction (upload separately; GL
// timestamps and wall time with glFinish) against OpenVDB's volumeToMesh on the same lattice,
// triangles, triangles per second, active blocks, GPU buffer bytes, and time(256³)/time(128³).
// Writes JSON; timings are medians of repeated runs after one warm-up.
#include <string>
#include <vector>

namespace tallow::app {

struct ProbeExtractionOptions {
  std::vector<std::string> fields{"blob", "candle"};
  std::vector<int> resolutions{64, 128, 256};
  int repeats = 5;
  std::string gl = "osmesa";
  std::string out;  ///< JSON file
};

int runProbeExtraction(const ProbeExtractionOptions& options);

}  // namespace tallow::app
