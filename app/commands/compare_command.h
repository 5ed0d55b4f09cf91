#pragma once
// `tallow compare A.exr B.exr --out FIG.png`: two renders of one scene side by side, tone mapped,
// each under its caption, and their difference in false colour with a scale bar
// (app/commands/comparison_figure.h), e.g. a frame against its reference, or VPL shadows off and on
// (docs/RESULTS.md). Needs gnuplot.
#include <string>
#include <vector>

namespace tallow::app {

struct CompareOptions {
  std::string a, b;                   ///< EXR files of one size; B is the one the difference is relative to
  std::vector<std::string> captions;  ///< for A and B (default: their file names)
  std::string title;
  std::string mask;         ///< EXR whose alpha ≥ 0.5 marks the compared pixels (a reference's _stderr.exr); empty: all
  double exposureEv = 0.0;  ///< before the ACES tone map
  double scale = 0.0;       ///< top of the colour scale as a fraction; 0: automatic
  std::string out;          ///< FIG.png
};

/// Returns the exit code; throws InputError with one line on bad input (unreadable or mismatched
/// images, gnuplot missing, a bad --scale), std::runtime_error when gnuplot fails.
int runCompare(const CompareOptions& options);

}  // namespace tallow::app
