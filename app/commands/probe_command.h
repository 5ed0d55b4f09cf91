#pragma once
// `tallow probe`: evaluates the BSSRDF models outside any scene — per configuration (`bssrdf`), and
// as diffuse-reflectance profiles of a planar medium (`profile`).
#include <cstdint>
#include <string>

namespace tallow::app {

struct ProbeBssrdfOptions {
  std::string model;               ///< standard | directional | pbd
  std::string precision;            ///< float | double; empty: double on the CPU, float with --gpu
  bool gpu = false;                ///< evaluate the GLSL through a GL context
  std::string gl = "osmesa";       ///< context for --gpu
  bool reciprocal = false;         ///< directional dipole: average with swapped arguments (§6.3)
  std::string in, out;
};

/// Reads CONFIGS.csv, evaluates every row, writes VALUES.csv (whole or not at all).
int runProbeBssrdf(const ProbeBssrdfOptions& options);

}  // namespace tallow::app
