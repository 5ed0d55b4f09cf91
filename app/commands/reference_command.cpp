#include "app/commands/reference_command.h"

#include <cmath>
#include <cstdio>
#include <algorithm>
#include <functional>
#include <map>
#include <stdexcept>

#include "app/commands/interrupt.h"
#include "app/commands/mesh_command.h"
#include "app/commands/progress.h"
#include "app/commands/provenance.h"
#include "app/commands/option_checks.h"
#include "app/config/input_error.h"
#include "gpu/image_error.h"
#include "gpu/image_io.h"
#include "sss/bssrdf/bssrdf.h"
#include "sss/field_objects.h"

namespace tallow::app {
namespace {

std::string number(double v) {
  char text[64];
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}

sss::ReferenceSettings referenceSettings(const ReferenceOptions& options, sss::FieldMeshes fieldMeshes) {
  sss::ReferenceSettings s;
  s.fieldMeshes = std::move(fieldMeshes);
  s.timeS = options.timeS;
  s.maxPasses = options.spp > 0 ? options.spp : 0;
  s.relError = options.relError.value_or(0.0);
  s.pointsPerPass = options.points;
  s.seed = options.seed;
  s.threads = options.threads;
  s.pixelFilter = options.pixelFilter == "centre" ? sss::PixelFilter::Centre : sss::PixelFilter::Box;
  s.emergentLight = options.emergent > 0;
  if (s.emergentLight) s.emitterPoints = options.emergent;
  return s;
}

/// `REF<suffix>.exr` beside `REF.exr`.
std::filesystem::path besideOutput(const std::filesystem::path& out, const std::string& suffix) {
  std::filesystem::path p = out;
  std::string name = out.stem().string();
  name += suffix;
  name += out.extension().string();
  p.replace_filename(name);
  return p;
}

/// "3.1%", or why there is no estimate yet (one pass has no variance).
std::string errorText(double relError) {
  if (std::isinf(relError)) return "not known after 1 pass";
  char text[32];
  std::snprintf(text, sizeof text, "%.3g%%", 100.0 * relError);
  return text;
}

}  // namespace

ReferenceTracker::ReferenceTracker(const ReferenceOptions& options, Progress& progress)
    : spp_(options.spp > 0 ? options.spp : 0), target_(options.relError.value_or(0.0)),
      progress_(progress) {
  progress_.setTotal(spp_);
}

bool ReferenceTracker::operator()(int passes, double relError) {
  // ε falls as 1/√passes: the passes it needs are passes · (ε / target)², and the stopping rule
  // waits for sss::ReferenceSettings::minPasses whatever ε says.
  int total = spp_;
  if (target_ > 0.0 && std::isfinite(relError) && passes >= 2) {
    const double needed = std::ceil(passes * (relError / target_) * (relError / target_));
    const int estimate = static_cast<int>(std::clamp(needed, static_cast<double>(std::max(passes, kMinPasses)), 1e9));
    total = total > 0 ? std::min(total, estimate) : estimate;
  }
  progress_.setTotal(total);
  std::string detail = "relative standard error " + errorText(relError);
  if (target_ > 0.0) detail += " (target " + errorText(target_) + ")";
  progress_.update(passes, detail);
  return !interrupted();
}

void validateReferenceOptions(const ReferenceOptions& options) {
  if (options.out.empty()) throw InputError("reference: --out REF.exr is required");
  if (options.spp != kNotGiven && options.spp < 1) throw InputError("--spp: must be at least 1");
  if (options.relError && !(std::isfinite(*options.relError) && *options.relError > 0.0))
    throw InputError("--rel-error: must be a positive number");
  if (options.spp == kNotGiven && !options.relError)
    throw InputError("reference: give --spp S (passes) or --rel-error E (relative standard error)");
  if (options.points < 0) throw InputError("--points: must be 0 (automatic) or more");
  if (options.threads < 0) throw InputError("--threads: must be at least 0");
  if (options.emergent < 0) throw InputError("--emergent: emitter points per object and pass must be at least 1");
  checkTime("--time", options.timeS);
}

std::filesystem::path standardErrorPath(const std::filesystem::path& out) { return besideOutput(out, "_stderr"); }

std::filesystem::path emergentPath(const std::filesystem::path& out) { return besideOutput(out, "_emergent"); }

gpu::Image readReferenceImage(const std::filesystem::path& file, const std::string& option) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) throw InputError(option + ": " + file.string() + " does not exist");
  gpu::Image image;
  try {
    image = gpu::readExr(file);
  } catch (const std::exception& e) {
    throw InputError(option + ": " + e.what());
  }
  // Every error against it would be undefined (and once read as 0: a false perfect match).
  if (const std::size_t bad = gpu::nonFinitePixels(image))
    throw InputError(option + ": " + file.string() + ": " + std::to_string(bad) +
                     " pixel(s) are NaN or infinite; a reference must be finite");
  return image;
}

gpu::Image readReferenceImage(const std::filesystem::path& file, int width, int height, const std::string& what,
                              const std::string& option) {
  gpu::Image image = readReferenceImage(file, option);
  if (image.width != width || image.height != height)
    throw InputError(option + ": " + file.string() + " is " + std::to_string(image.width) + "x" +
                     std::to_string(image.height) + " but " + what + " renders " + std::to_string(width) + "x" +
                     std::to_string(height));
  return image;
}

ReferenceImages readReferencePair(const std::filesystem::path& file, int width, int height, const std::string& what,
                                  const std::string& option, bool plainAllowed) {
  std::error_code ec;
  if (plainAllowed && std::filesystem::is_regular_file(file, ec) &&
      !std::filesystem::exists(standardErrorPath(file), ec)) {
    ReferenceImages plain{readReferenceImage(file, width, height, what, option), gpu::Image(width, height), true};
    for (glm::vec4& p : plain.standardError.pixels) p = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    return plain;
  }
  return {readReferenceImage(file, width, height, what, option),
          readReferenceImage(standardErrorPath(file), width, height, what, option)};
}

std::string emergentFlag() {
  std::string flag = "--emergent{";
  flag += std::to_string(sss::kDefaultEmitterPoints);
  flag += "}";
  return flag;
}

sss::FieldMeshes referenceFieldMeshes(const ReferenceOptions& options, const LoadedScene& loaded) {
  if (options.cpuMesher) return {};
  return drawnFieldMeshes(loaded, options.scene.shaderDir, options.timeS, options.gl);
}

sss::ReferenceResult computeReference(const ReferenceOptions& options, const sss::ReferenceProgress& progress,
                                      const sss::FieldMeshes* fieldMeshes) {
  validateReferenceOptions(options);
  const LoadedScene loaded = loadScene(options.scene);
  const sss::ReferenceSettings settings =
      referenceSettings(options, fieldMeshes ? *fieldMeshes : referenceFieldMeshes(options, loaded));
  try {
    return sss::renderReference(loaded.config.scene, loaded.config.render, settings, progress);
  } catch (const std::invalid_argument& e) {
    throw InputError(e.what());
  }
}

int runReference(const ReferenceOptions& options) {
  validateReferenceOptions(options);
  const std::filesystem::path out(options.out);
  // Written as OpenEXR whatever the name says, so the name must say it (REF_stderr.exr beside it too,
  // and REF_emergent.exr with --emergent: their names are checked now, not after the integration).
  checkOutputFile("--out", out, {".exr"});
  checkOutputName("--out", standardErrorPath(out));
  if (options.emergent > 0) checkOutputName("--out", emergentPath(out));
  const LoadedScene loaded = loadScene(options.scene);
  const sss::ReferenceSettings settings = referenceSettings(options, referenceFieldMeshes(options, loaded));
  const bool anyField = sss::FieldObjects::any(loaded.config.scene);
  sss::ReferenceResult r;
  // SIGINT/SIGTERM end the integration after the pass in hand; the passes done are written as a
  // valid reference, its pass count and error in the metadata.
  const InterruptScope interruptScope;
  {
    Progress progress("reference", "pass", 0);
    ReferenceTracker tracker(options, progress);
    try {
      r = sss::renderReference(loaded.config.scene, loaded.config.render, settings, std::ref(tracker));
    } catch (const std::invalid_argument& e) {
      throw InputError(e.what());
    }
  }
  std::map<std::string, std::string> attributes{
      {"tallow.preset", loaded.presetName},
      {"tallow.renderer", "tallow reference (CPU, Embree + TBB)"},
      {"tallow.spp", std::to_string(r.passes)},
      {"tallow.passes", std::to_string(r.passes)},
      {"tallow.pixel_filter", options.pixelFilter},
      {"tallow.points_per_pass", std::to_string(r.pointsPerPass)},
      {"tallow.near_field_points", number(r.nearFieldPoints)},
      {"tallow.rel_error", number(r.relError)},
      {"tallow.rel_error_statistic", sss::kReferenceErrorStatistic},
      {"tallow.seed", std::to_string(options.seed)},
      {"tallow.time_s", number(options.timeS)},
      {"tallow.model", std::string(sss::bssrdfModelName(loaded.config.render.sss.model))},
      {"tallow.triangles", std::to_string(r.triangles)},
      {"tallow.field_mesher", !anyField ? "none" : options.cpuMesher ? "OpenVDB volumeToMesh" : "GPU dual contouring"},
      {"tallow.seconds", number(r.seconds)},
      {"tallow.emergent", r.emitterPoints > 0 ? "on" : "off"},
      {"tallow.version", tallowVersion()},
      {"tallow.command_line", commandLine()},
      {"tallow.date", runStartUtc()},
      {"tallow.complete", interrupted() ? "no" : "yes"}};
  if (interrupted()) attributes["tallow.stopped_by"] = interruptName();
  if (r.emitterPoints > 0) {
    attributes["tallow.emitter_points"] = std::to_string(r.emitterPoints);
    attributes["tallow.emergent_pixels"] = std::to_string(r.emergentPixels);
    attributes["tallow.emergent_rel_error"] = number(r.emergentRelError);
    attributes["tallow.emergent_rel_error_statistic"] = sss::kEmergentErrorStatistic;
  }
  if (r.translucentPixels > 0 && r.nearFieldPoints < 1.0)
    std::fprintf(stderr,
                 "tallow: warning: only %.2g surface point(s) per pass fall within 1/sigma_t' of a pixel's surface point: "
                 "the mean and its error estimate are biased low until many passes have run; raise --points "
                 "(or leave it out to choose it automatically)\n",
                 r.nearFieldPoints);
  // The pair (or triple) whole or not at all: a reference without its standard error is unusable.
  std::vector<gpu::ExrOutput> files = {{out, &r.radiance, gpu::ExrPixelType::Float, attributes},
                                       {standardErrorPath(out), &r.standardError, gpu::ExrPixelType::Float, attributes}};
  if (r.emitterPoints > 0) files.push_back({emergentPath(out), &r.emergent, gpu::ExrPixelType::Float, attributes});
  gpu::writeExrFiles(files);
  std::printf("tallow: reference of %s (%dx%d): %d pass(es) x %d points, relative standard error %s, %.1f s -> %s\n",
              loaded.presetName.c_str(), r.radiance.width, r.radiance.height, r.passes, r.pointsPerPass,
              errorText(r.relError).c_str(), r.seconds, options.out.c_str());
  if (r.emitterPoints > 0)
    std::printf("tallow: emergent light: %d emitter points per object and pass, %d receiver pixel(s) lit, relative "
                "standard error %s -> %s\n",
                r.emitterPoints, r.emergentPixels, number(r.emergentRelError).c_str(), emergentPath(out).string().c_str());
  if (interrupted()) {
    std::fprintf(stderr, "tallow: reference stopped by %s after %d pass(es); wrote what they hold (tallow.complete = no)\n",
                 interruptName(), r.passes);
    return interruptExitCode();
  }
  return 0;
}

}  // namespace tallow::app
