#pragma once
// `tallow bench`: speed against error (issue 6). For every method and every combination of the
// swept settings, times the frames after a warm-up frame and a restart of the accumulation, and
// compares each frame with a converged CPU reference (`tallow reference`) over the object pixels:
// bench.csv, convergence.csv, bench.json, one folder of pictures per row (rows/<row>/) and, with
// gnuplot, plots. Each reference and each row is written as soon as it is done (the tables and
// bench.json rewritten whole); SIGINT or SIGTERM stops after the reference pass in hand or drops
// the row in hand, writes what is done and exits with 130 or 143. docs/commands.md.
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "app/commands/reference_command.h"
#include "app/config/setup.h"

namespace tallow::app {

/// Fewest timed frames: the first, at least two more, and a median worth the name.
inline constexpr int kMinBenchFrames = 5;

struct BenchOptions {
  SceneOptions scene;
  std::string gl = "osmesa";
  std::string outDir;
  double timeS = 0.0;
  std::vector<std::string> methods;  ///< values of `method`; empty: every choice the registry has
  std::vector<std::string> sweeps;   ///< "key=v1,v2,…"
  int frames = kMinBenchFrames;      ///< timed frames; raised to sss.frames + 2 for progressive methods
  std::string reference;             ///< REF.exr (REF_stderr.exr beside it); empty: compute one
  std::optional<double> refRelError;  ///< --ref-rel-error; unset: not given (a NaN given is refused)
  int refSpp = kNotGiven;            ///< --ref-spp
  int refPoints = 0;                 ///< --ref-points (0: automatic)
  bool equalTime = false;            ///< also run the reference for each row's first-frame time
  /// --receivers: the reference also integrates the emergent light onto the opaque receivers
  /// (`tallow reference --emergent`), and each row compares its VPL term (the last frame minus the
  /// same frame with vpl.count = 0) with it over the receiver pixels (issue 7).
  bool receivers = false;
};

/// A parsed --sweep.
struct Sweep {
  std::string key;
  std::vector<std::string> values;
  /// A method knob (`sss.*` other than `sss.model`, `vpl.*`, `sslpv.*`): the ground truth does not depend on it, so
  /// its values share one reference. Any other key changes the picture the methods approximate.
  bool knob = false;
};

/// Parses "key=v1,v2,…"; throws InputError with one line when there is no '=', no key, or an empty
/// value. The key itself is checked later, by the registry.
Sweep parseSweep(const std::string& text);

/// Returns the exit code; throws InputError / std::runtime_error with one line. Bad input is found
/// before anything is written; every file is written atomically.
int runBench(const BenchOptions& options);

}  // namespace tallow::app
