#pragma once
// `tallow probe maps`: the cost of the scattered radiosity maps (issue 5, point 9). For each K
// (sss.maps) and N (sss.samples) the preset is loaded through the parameter registry (as `capture`
// does with --set), one warm-up frame is rendered, then `repeats` frames in which the maps keep
// accumulating (sss.frames is raised so they never converge), so every timed frame runs
// sss.light_gbuffer and sss.maps. Reports the median GPU ms of sss.light_gbuffer, sss.maps and
// surface, the maps' memory, the map texels the estimator shaded (read back from the maps' alpha)
// and an upper bound on BSSRDF evaluations per second; fits sss.maps ms = a + b·K·N (the paper's
// Fig. 13 finds the cost linear in K). Writes JSON.
#include <string>
#include <vector>

#include "app/config/setup.h"

namespace tallow::app {

struct ProbeMapsOptions {
  SceneOptions scene;            ///< --preset, --set, --size, --shader-dir (sss.maps/samples/frames are set here)
  std::vector<int> maps{4, 8, 16, 32};  ///< --k
  std::vector<int> samples{1, 4, 16};   ///< --n
  int mapSize = 0;               ///< --map-size: sss.map_size, 0 = the preset's
  int repeats = 5;
  std::string gather;            ///< --gather: sss.gather, empty = the preset's
  std::string gl = "osmesa";
  std::string out;  ///< JSON file
};

int runProbeMaps(const ProbeMapsOptions& options);

/// Least squares y = intercept + slope·x, with R² (1 when y is constant and fitted exactly).
struct LinearFit {
  double intercept = 0.0, slope = 0.0, r2 = 0.0;
};
LinearFit fitLine(const std::vector<double>& x, const std::vector<double>& y);

/// Least squares y = intercept + a·x1 + b·x2, with R²; a = b = 0 when x1, x2 are collinear.
struct PlaneFit {
  double intercept = 0.0, a = 0.0, b = 0.0, r2 = 0.0;
};
PlaneFit fitPlane(const std::vector<double>& x1, const std::vector<double>& x2, const std::vector<double>& y);

}  // namespace tallow::app
