#pragma once
// `tallow reference`: the CPU ground truth of a preset (sss/reference/reference_integrator.h) with the same
// camera, size and parameters as `capture`, written as REF.exr (32-bit float, linear) and
// REF_stderr.exr (the per-pixel standard error of the mean), with --emergent also REF_emergent.exr
// (the light leaving the translucent objects onto the receivers alone), with the passes, points per
// pass, error estimate, seed and provenance in the EXR header. Progress (pass, error, time left) on
// stderr; SIGINT or SIGTERM stops after the pass in hand and writes the passes done, marked
// tallow.complete = no, with the exit status 130 or 143. docs/reference.md.
#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>

#include "app/commands/progress.h"
#include "app/config/setup.h"
#include "gpu/image.h"
#include "sss/reference/reference_integrator.h"

namespace tallow::app {

/// --spp not given.
inline constexpr int kNotGiven = std::numeric_limits<int>::min();

struct ReferenceOptions {
  SceneOptions scene;
  double timeS = 0.0;
  int spp = kNotGiven;  ///< passes (--spp)
  std::optional<double> relError;  ///< --rel-error; unset: not given (a NaN given is refused)
  int points = 0;           ///< --points: surface points per translucent object and pass; 0: automatic
  std::uint64_t seed = 1;   ///< --seed
  int threads = 0;          ///< --threads; 0: all cores
  std::string pixelFilter = "box";  ///< --pixel-filter: box (the pixel's square) or centre
  /// --emergent[=N]: emitter points per translucent object and pass of the emergent light onto the
  /// receivers (sss::kDefaultEmitterPoints when given without a value); 0: off.
  int emergent = 0;
  /// --cpu-mesher: mesh field objects with OpenVDB's volumeToMesh instead of taking the triangles
  /// the GPU draws (drawnFieldMeshes), as before; their silhouettes and creases differ by a pixel.
  bool cpuMesher = false;
  std::string gl = "osmesa";  ///< --gl: the context that contours the field objects
  std::string out;          ///< REF.exr
};

/// Checks the options that need no scene; throws InputError with one line (`--spp: must be at
/// least 1`, `--rel-error: must be a positive number`, neither given, --points < 0, --time out of
/// range, an --out that is not a writable .exr, …).
void validateReferenceOptions(const ReferenceOptions& options);

/// REF_stderr.exr beside REF.exr.
std::filesystem::path standardErrorPath(const std::filesystem::path& out);

/// REF_emergent.exr beside REF.exr (with --emergent).
std::filesystem::path emergentPath(const std::filesystem::path& out);

/// A file of a reference given with `option` (REF.exr, REF_stderr.exr, …) read whole; throws
/// InputError with one line (`--reference: REF.exr does not exist`, the EXR reader's message).
gpu::Image readReferenceImage(const std::filesystem::path& file, const std::string& option = "--reference");

/// The same, checked against the size `what` renders: throws InputError naming the file and both
/// sizes when they differ.
gpu::Image readReferenceImage(const std::filesystem::path& file, int width, int height, const std::string& what,
                              const std::string& option = "--reference");

/// REF.exr and REF_stderr.exr (whose alpha marks the object pixels compared), checked against the
/// size `what` renders: throws InputError naming the file and both sizes when they differ. With
/// `plainAllowed`, a REF.exr without REF_stderr.exr beside it (a stored capture as a golden image)
/// is read alone: every pixel compared (standardError then has alpha 1 and colour 0 everywhere).
struct ReferenceImages {
  gpu::Image radiance, standardError;
  bool plain = false;  ///< no REF_stderr.exr: every pixel is compared
};
ReferenceImages readReferencePair(const std::filesystem::path& file, int width, int height, const std::string& what,
                                  const std::string& option = "--reference", bool plainAllowed = false);

/// The option that turns the emergent light on, with its default emitter count: `--emergent{N}`
/// (CLI11's flag-with-value syntax: `--emergent` gives N, `--emergent=M` gives M).
std::string emergentFlag();

/// The integrator's progress callback of a command: reports each pass to `progress` (with the
/// passes the --rel-error target needs, estimated from ε ∝ 1/√passes) and stops the integration
/// once a stop was requested (app/commands/interrupt.h).
class ReferenceTracker {
 public:
  ReferenceTracker(const ReferenceOptions& options, Progress& progress);
  bool operator()(int passes, double relError);

 private:
  /// sss::ReferenceSettings::minPasses: passes the --rel-error stop always waits for.
  static constexpr int kMinPasses = sss::kDefaultMinPasses;
  int spp_;
  double target_;
  Progress& progress_;
};

/// The field meshes the reference of `loaded` integrates over: the GPU's (drawnFieldMeshes in a
/// hidden context of options.gl) unless options.cpuMesher (then none: the integrator meshes them).
sss::FieldMeshes referenceFieldMeshes(const ReferenceOptions& options, const LoadedScene& loaded);

/// Loads the scene as `capture` does and integrates it; nothing written. Field objects take the
/// triangles of `fieldMeshes` when given, else those of referenceFieldMeshes.
sss::ReferenceResult computeReference(const ReferenceOptions& options, const sss::ReferenceProgress& progress = {},
                                      const sss::FieldMeshes* fieldMeshes = nullptr);

/// Returns the exit code; throws InputError / std::runtime_error with one line.
int runReference(const ReferenceOptions& options);

}  // namespace tallow::app
