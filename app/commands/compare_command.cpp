#include "app/commands/compare_command.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <optional>

#include "app/commands/capture_command.h"
#include "app/commands/comparison_figure.h"
#include "app/commands/frame_stats.h"
#include "app/commands/gnuplot.h"
#include "app/commands/option_checks.h"
#include "app/config/input_error.h"
#include "app/config/registry.h"
#include "gpu/atomic_file.h"
#include "gpu/image_error.h"
#include "gpu/image_io.h"

namespace tallow::app {
namespace {

/// The EXR reader's messages start with the file's name: an option's name goes before it, no more.
gpu::Image readInput(const std::string& file, const std::string& option = "") {
  try {
    return gpu::readExr(file);
  } catch (const std::exception& e) {
    throw InputError(option.empty() ? std::string(e.what()) : option + ": " + e.what());
  }
}

std::string sizeText(const gpu::Image& i) { return std::to_string(i.width) + "x" + std::to_string(i.height); }


/// A file's caption by default: its folder and name ("golden/frame_0000.exr"), since two captures'
/// frames have the same name.
std::string defaultCaption(const std::string& file) {
  const std::filesystem::path p(file);
  const std::filesystem::path folder = p.parent_path().filename();
  return folder.empty() ? p.filename().string() : (folder / p.filename()).string();
}

void writeFigure(const CompareOptions& o, const gpu::Image& a, const gpu::Image& b, const gpu::Image* mask) {
  FigureSpec spec;
  spec.title = o.title;
  spec.toneMap.exposureEv = static_cast<float>(o.exposureEv);
  spec.mask = mask;
  spec.scale = o.scale;
  const auto caption = [&](std::size_t i, const std::string& file) {
    return i < o.captions.size() ? o.captions[i] : defaultCaption(file);
  };
  spec.images = {{&a, caption(0, o.a)}, {&b, caption(1, o.b)}};
  // Short, whatever the captions: the panel is one picture wide.
  spec.differences = {{&a, &b, "|left − right|", 1}};
  spec.scaleLabel = "|Δ| / RMS of the right picture";
  writeComparisonFigure(std::filesystem::path(o.out), spec);
  std::printf("tallow: wrote %s\n", o.out.c_str());
}

/// The golden-image test: one line, on stdout within the thresholds, on stderr past them.
int testThresholds(const CompareOptions& o, const nlohmann::json& error) {
  const double relRmse = error["rel_rmse"].is_number() ? error["rel_rmse"].get<double>()
                                                       : std::numeric_limits<double>::infinity();
  const auto newFireflies = error["new_fireflies"].get<long long>();
  char figures[160];
  std::snprintf(figures, sizeof figures, "relative RMSE %.4g, %lld new firefl%s", relRmse, newFireflies,
                newFireflies == 1 ? "y" : "ies");
  std::string past;
  if (o.maxRelRmse && !(relRmse <= *o.maxRelRmse)) past = "relative RMSE above --max-rel-rmse " + formatNumber(*o.maxRelRmse);
  else if (o.maxNewFireflies && newFireflies > *o.maxNewFireflies)
    past = "more new fireflies than --max-new-fireflies " + std::to_string(*o.maxNewFireflies);
  if (!past.empty()) {
    std::fprintf(stderr, "tallow: compare: %s differs from %s: %s (%s)\n", o.a.c_str(), o.b.c_str(), figures, past.c_str());
    return kImagesDiffer;
  }
  std::printf("tallow: compare: %s matches %s within the thresholds: %s\n", o.a.c_str(), o.b.c_str(), figures);
  return 0;
}

}  // namespace

int runCompare(const CompareOptions& o) {
  const bool tested = o.maxRelRmse || o.maxNewFireflies;
  if (o.out.empty() && o.json.empty() && !tested)
    throw InputError("compare: --out FIG.png, --json ERR.json or a threshold (--max-rel-rmse) is required");
  if (o.maxRelRmse && !(*o.maxRelRmse >= 0.0 && std::isfinite(*o.maxRelRmse)))
    throw InputError("--max-rel-rmse: must be a finite fraction >= 0, e.g. 0.02");
  if (o.maxNewFireflies && *o.maxNewFireflies < 0) throw InputError("--max-new-fireflies: must be >= 0");
  if (!o.out.empty() && std::filesystem::path(o.out).extension() != ".png")
    throw InputError("--out: expected a .png file, got \"" + o.out + "\"");
  if (!o.json.empty()) checkOutputFile("--json", o.json, {".json"});
  if (!o.out.empty()) {
    checkOutputFile("--out", o.out, {".png"});
    if (!gnuplotAvailable()) throw InputError("compare: gnuplot is not installed (apt-get install gnuplot-nox)");
  }
  if (o.captions.size() > 2) throw InputError("--caption: give at most two, for A and B");
  if (!(o.scale >= 0.0) || !std::isfinite(o.scale)) throw InputError("--scale: must be a positive fraction (0: automatic)");
  if (!std::isfinite(o.exposureEv) || std::abs(o.exposureEv) > 20.0) throw InputError("--exposure-ev: must be in [-20, 20]");
  const gpu::Image a = readInput(o.a);
  const gpu::Image b = readInput(o.b);
  if (a.width != b.width || a.height != b.height)
    throw InputError("compare: " + o.a + " is " + sizeText(a) + " but " + o.b + " is " + sizeText(b));
  std::optional<gpu::Image> mask;
  if (!o.mask.empty()) {
    mask = readInput(o.mask, "--mask");
    if (mask->width != a.width || mask->height != a.height)
      throw InputError("--mask: " + o.mask + " is " + sizeText(*mask) + ", the images " + sizeText(a));
  }
  // Without a mask every pixel counts (alpha 1 everywhere).
  gpu::Image all = a;
  for (glm::vec4& p : all.pixels) p = glm::vec4(1.0f);
  const gpu::Image& pixels = mask ? *mask : all;
  if (gpu::objectPixels(pixels) == 0) throw InputError("--mask: " + o.mask + " marks no pixel (alpha >= 0.5)");
  // A NaN or infinite pixel makes the error undefined: refused, or left out and said so.
  const std::size_t badA = gpu::nonFinitePixels(a, &pixels), badB = gpu::nonFinitePixels(b, &pixels);
  if (badA + badB > 0) {
    std::string which;
    if (badA) which = o.a + " has " + std::to_string(badA);
    if (badB) which += (badA ? ", " : "") + o.b + " has " + std::to_string(badB);
    if (!o.ignoreNonFinite)
      throw InputError("compare: " + which + " NaN or infinite pixel(s) among those compared, so the error is "
                       "undefined (--ignore-non-finite leaves them out)");
    std::fprintf(stderr, "tallow: compare: left out the NaN or infinite pixels (%s)\n", which.c_str());
  }
  gpu::ImageErrorOptions errorOptions;
  errorOptions.skipNonFinite = o.ignoreNonFinite;
  const nlohmann::json error = referenceErrorRecord(a, b, pixels, errorOptions);
  if (!o.json.empty()) {
    const nlohmann::json record{{"a", o.a}, {"b", o.b}, {"mask", o.mask.empty() ? nlohmann::json(nullptr) : nlohmann::json(o.mask)},
                                {"error", error}};
    gpu::writeTextFileAtomically(o.json, record.dump(2) + "\n");
    std::printf("tallow: wrote %s\n", o.json.c_str());
  }
  if (!o.out.empty()) writeFigure(o, a, b, mask ? &*mask : nullptr);
  return tested ? testThresholds(o, error) : 0;
}

}  // namespace tallow::app
