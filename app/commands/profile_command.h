#pragma once
// `tallow probe profile`: diffuse reflectance R_d of a planar, semi-infinite medium lit by a ray
// at the origin at angle θ (x axis in the plane of incidence), along the x axis and as a 2D map —
// the directional-dipole paper's Figs. 4, 5, 6 and 13 — for an analytic model or the volumetric
// Monte Carlo reference (`--model mc`). Writes CSV and, when gnuplot is installed, PNG plots.
#include <cstdint>
#include <string>

namespace tallow::app {

struct ProbeProfileOptions {
  std::string model;     ///< standard | directional | pbd | mc
  std::string material;  ///< a name from materials.csv (then `band` picks the colour band) …
  int band = 0;          ///< 0 red, 1 green, 2 blue
  double sigmaA = -1.0;  ///< … or explicit coefficients [mm⁻¹]
  double sigmaS = -1.0;
  double g = 0.0;
  double eta = 1.0;
  double thetaDeg = 0.0;
  double extentMm = 40.0;  ///< x from −extent/2 to extent/2; the map covers that square
  int bins = 200;          ///< samples along x and per side of the map
  std::uint64_t photons = 1000000;  ///< --model mc
  std::uint64_t seed = 1;
  bool plots = true;
  std::string out;  ///< folder
};

int runProbeProfile(const ProbeProfileOptions& options);

}  // namespace tallow::app
