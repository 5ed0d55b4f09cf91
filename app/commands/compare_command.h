#pragma once
// `tallow compare A.exr B.exr --out FIG.png`: two renders of one scene side by side, tone mapped,
// each under its caption, and their difference in false colour with a scale bar
// (app/commands/comparison_figure.h), e.g. a frame against its reference, or VPL shadows off and on
// (docs/RESULTS.md). Needs gnuplot. `--json ERR.json` writes A's error against B over the mask as
// capture's per-frame "reference_error" has it (app/commands/frame_stats.h), e.g. for frames that
// another build rendered (scripts/results_animated.py).
#include <optional>
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
  std::string out;          ///< FIG.png (empty: no figure; then json is needed)
  std::string json;         ///< ERR.json (empty: none)
  /// --ignore-non-finite: leave out the compared pixels where A or B is NaN or infinite (counted and
  /// printed); without it such pixels make the comparison fail (the error is undefined).
  bool ignoreNonFinite = false;
  /// A test's thresholds (issue 40): past either, runCompare says so in one line on stderr and
  /// returns kImagesDiffer (the figure and the JSON asked for are still written, for the CI's
  /// artefacts). Within them it prints one line on stdout. Unset: no test.
  std::optional<double> maxRelRmse;
  std::optional<long long> maxNewFireflies;
};

/// runCompare's exit code when A is past a threshold (1 is bad input, 2 a mistyped command line).
inline constexpr int kImagesDiffer = 3;

/// Returns the exit code (0, or kImagesDiffer); throws InputError with one line on bad input
/// (unreadable or mismatched images, none of --out, --json or a threshold, a negative threshold, gnuplot missing for --out, a bad --scale, a mask with no
/// pixel, NaN or infinite pixels compared without --ignore-non-finite), std::runtime_error when
/// gnuplot fails. Nothing is written on a failure.
int runCompare(const CompareOptions& options);

}  // namespace tallow::app
