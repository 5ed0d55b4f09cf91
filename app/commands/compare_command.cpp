#include "app/commands/compare_command.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "app/commands/capture_command.h"
#include "app/commands/comparison_figure.h"
#include "app/commands/frame_stats.h"
#include "app/commands/gnuplot.h"
#include "app/commands/option_checks.h"
#include "app/config/input_error.h"
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

}  // namespace

int runCompare(const CompareOptions& o) {
  if (o.out.empty() && o.json.empty()) throw InputError("compare: --out FIG.png or --json ERR.json is required");
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
  if (!o.json.empty()) {
    const nlohmann::json record{{"a", o.a}, {"b", o.b}, {"mask", o.mask.empty() ? nlohmann::json(nullptr) : nlohmann::json(o.mask)},
                                {"error", referenceErrorRecord(a, b, pixels, errorOptions)}};
    gpu::writeTextFileAtomically(o.json, record.dump(2) + "\n");
    std::printf("tallow: wrote %s\n", o.json.c_str());
  }
  if (o.out.empty()) return 0;
  const std::filesystem::path out(o.out);

  FigureSpec spec;
  spec.title = o.title;
  spec.toneMap.exposureEv = static_cast<float>(o.exposureEv);
  spec.mask = mask ? &*mask : nullptr;
  spec.scale = o.scale;
  const auto caption = [&](std::size_t i, const std::string& file) {
    return i < o.captions.size() ? o.captions[i] : std::filesystem::path(file).filename().string();
  };
  spec.images = {{&a, caption(0, o.a)}, {&b, caption(1, o.b)}};
  // Short, whatever the captions: the panel is one picture wide.
  spec.differences = {{&a, &b, "|left − right|", 1}};
  spec.scaleLabel = "|Δ| / RMS of the right picture";
  writeComparisonFigure(out, spec);
  std::printf("tallow: wrote %s\n", o.out.c_str());
  return 0;
}

}  // namespace tallow::app
