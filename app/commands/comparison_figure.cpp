#include "app/commands/comparison_figure.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "app/commands/gnuplot.h"
#include "gpu/atomic_file.h"
#include "gpu/image_error.h"
#include "gpu/image_io.h"

namespace tallow::app {
namespace {

// Layout in pixels. Panels are at least kMinPanel wide (small renders enlarged, pixel for pixel)
// and at most kMaxPanel (a large one shrunk: the figure is an overview; the EXR holds the pixels).
constexpr int kMinPanel = 240, kMaxPanel = 360;
constexpr int kGap = 12, kCaption = 26, kTitle = 34, kMargin = 10;
constexpr int kColourBar = 130;  ///< right of the differences: the bar, its tick labels and its label
/// A sequential palette that stays readable in grey and for colour-blind readers: five stops of
/// the perceptually uniform "viridis" ramp (van der Walt and Smith, matplotlib), 0 → top.
constexpr const char* kPalette =
    "set palette defined (0 '#440154', 1 '#3b528b', 2 '#21918c', 3 '#5ec962', 4 '#fde725')\n";

void writeBytes(const std::filesystem::path& file, const void* data, std::size_t bytes) {
  std::FILE* f = std::fopen(file.c_str(), "wb");
  if (!f) throw std::runtime_error("cannot write " + file.string());
  const bool ok = std::fwrite(data, 1, bytes, f) == bytes;
  if (std::fclose(f) != 0 || !ok) throw std::runtime_error("cannot write " + file.string());
}

/// A tick label: gnuplot reads tic labels as formats, so the percent sign is doubled.
std::string percentTic(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g%%%%", v);
  return text;
}

}  // namespace

std::vector<float> relativeDifference(const gpu::Image& image, const gpu::Image& reference, const gpu::Image* mask) {
  if (image.width != reference.width || image.height != reference.height ||
      (mask && (mask->width != image.width || mask->height != image.height)))
    throw std::invalid_argument("comparison: the images differ in size");
  const auto inside = [&](std::size_t i) { return !mask || mask->pixels[i].a >= gpu::kObjectMaskAlpha; };
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < reference.pixels.size(); ++i)
    if (inside(i)) {
      const glm::dvec3 r(reference.pixels[i]);
      sum += glm::dot(r, r);
      ++n;
    }
  const double rms = n > 0 ? std::sqrt(sum / static_cast<double>(n)) : 0.0;
  std::vector<float> out(image.pixels.size(), std::numeric_limits<float>::quiet_NaN());
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (!inside(i)) continue;
    const double e = glm::length(glm::dvec3(image.pixels[i]) - glm::dvec3(reference.pixels[i]));
    out[i] = static_cast<float>(rms > 0.0 ? e / rms : (e > 0.0 ? std::numeric_limits<double>::infinity() : 0.0));
  }
  return out;
}

double niceScale(std::vector<float> values, double quantile) {
  std::erase_if(values, [](float v) { return !std::isfinite(v); });
  if (values.empty()) return 1.0;
  const auto k = static_cast<std::size_t>(std::clamp(quantile, 0.0, 1.0) * static_cast<double>(values.size() - 1));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
  const double q = values[k];
  if (!(q > 0.0)) return 1.0;
  const double decade = std::pow(10.0, std::floor(std::log10(q)));
  // The values are floats: 0.2f is 0.2000000030, which must still round to 0.2.
  for (const double step : {1.0, 2.0, 5.0, 10.0})
    if (step * decade >= q * (1.0 - 1e-6)) return step * decade;
  return 10.0 * decade;
}

bool writeComparisonFigure(const std::filesystem::path& png, const FigureSpec& spec) {
  if (spec.images.empty()) throw std::invalid_argument("comparison: no image");
  if (!gnuplotAvailable()) return false;
  const int w = spec.images.front().image->width, h = spec.images.front().image->height;
  for (const FigureImage& i : spec.images)
    if (i.image->width != w || i.image->height != h) throw std::invalid_argument("comparison: the images differ in size");

  // Differences, in percent, and one scale for all of them.
  std::vector<std::vector<float>> differences;
  std::vector<float> all;
  for (const FigureDifference& d : spec.differences) {
    differences.push_back(relativeDifference(*d.image, *d.reference, spec.mask));
    for (float& v : differences.back()) v *= 100.0f;
    all.insert(all.end(), differences.back().begin(), differences.back().end());
  }
  // niceScale of values in percent is the percent scale itself (1, 2, 5 × 10^k either way).
  const double topPercent = spec.scale > 0.0 ? 100.0 * spec.scale : niceScale(all, 0.99);

  int columns = static_cast<int>(spec.images.size());
  for (const FigureDifference& d : spec.differences) columns = std::max(columns, d.column + 1);
  const int rows = spec.differences.empty() ? 1 : 2;
  const int panelW = std::clamp(w, kMinPanel, kMaxPanel);
  const int panelH = std::max(1, static_cast<int>(std::lround(static_cast<double>(panelW) * h / w)));
  const int width = 2 * kMargin + columns * panelW + (columns - 1) * kGap + (rows == 2 ? kColourBar : 0);
  const int height = kTitle + rows * (panelH + kCaption) + (rows - 1) * kGap + kMargin;

  // The pixels, as raw files gnuplot reads from the run's private folder (removed with it).
  const std::filesystem::path folder = png.has_parent_path() ? png.parent_path() : std::filesystem::path(".");
  GnuplotRun run(folder);
  std::vector<std::string> imageFiles, differenceFiles;
  for (std::size_t i = 0; i < spec.images.size(); ++i) {
    const std::vector<std::uint8_t> rgb = gpu::toneMappedRgb8(*spec.images[i].image, spec.toneMap);
    const std::string name = "image" + std::to_string(i) + ".rgb";
    writeBytes(run.dataPath(name), rgb.data(), rgb.size());
    imageFiles.push_back(run.dataLiteral(name));
  }
  for (std::size_t i = 0; i < differences.size(); ++i) {
    const std::string name = "difference" + std::to_string(i) + ".f32";
    writeBytes(run.dataPath(name), differences[i].data(), differences[i].size() * sizeof(float));
    differenceFiles.push_back(run.dataLiteral(name));
  }

  const auto sx = [&](double px) { return px / width; };
  const auto sy = [&](double py) { return 1.0 - py / height; };  // py from the top
  const auto panelX = [&](int column) { return kMargin + column * (panelW + kGap); };
  const auto panelTop = [&](int row) { return kTitle + row * (panelH + kCaption + kGap) + kCaption; };
  run.draw(
      [&](std::FILE* f, const std::vector<std::string>& output) {
        std::fprintf(f, "set terminal pngcairo size %d,%d font ',10'\nset output %s\n", width, height, output[0].c_str());
        std::fprintf(f, "%s", kPalette);
        std::fprintf(f, "set termoption noenhanced\n");  // captions are text: "sss.maps_4" has no subscript
        std::fprintf(f, "set multiplot title %s font ',12'\n", gnuplotString(spec.title).c_str());
        std::fprintf(f, "unset key\nunset border\nunset tics\nset xrange [-0.5:%d.5]\nset yrange [-0.5:%d.5]\n", w - 1,
                     h - 1);
        const auto place = [&](int column, int row) {
          const double x0 = panelX(column), top = panelTop(row);
          std::fprintf(f, "set lmargin at screen %.6f\nset rmargin at screen %.6f\n", sx(x0), sx(x0 + panelW));
          std::fprintf(f, "set tmargin at screen %.6f\nset bmargin at screen %.6f\n", sy(top), sy(top + panelH));
        };
        for (std::size_t i = 0; i < spec.images.size(); ++i) {
          place(static_cast<int>(i), 0);
          std::fprintf(f, "set title %s offset 0,-0.6\nunset colorbox\n", gnuplotString(spec.images[i].caption).c_str());
          std::fprintf(f, "plot %s binary array=(%d,%d) format='%%uchar%%uchar%%uchar' flipy with rgbimage\n",
                       imageFiles[i].c_str(), w, h);
        }
        if (!differences.empty()) {
          std::fprintf(f, "set cbrange [0:%.9g]\n", topPercent);
          // Ticks at 0, a quarter, …, the top; the top one marks that larger values share its colour.
          std::fprintf(f, "set cbtics (");
          for (int t = 0; t <= 4; ++t) {
            const double v = topPercent * t / 4.0;
            std::fprintf(f, "%s%s %.9g", t ? ", " : "", gnuplotString((t == 4 ? "≥ " : "") + percentTic(v)).c_str(), v);
          }
          std::fprintf(f, ") out nomirror\n");
          const double barX = panelX(columns - 1) + panelW + kGap;
          std::fprintf(f, "set colorbox vertical user origin screen %.6f,%.6f size screen %.6f,%.6f\n", sx(barX),
                       sy(panelTop(1) + panelH), sx(14), static_cast<double>(panelH) / height);
          std::fprintf(f, "set cblabel %s offset -1,0\n", gnuplotString(spec.scaleLabel).c_str());
          for (std::size_t i = 0; i < differences.size(); ++i) {
            place(spec.differences[i].column, 1);
            std::fprintf(f, "set title %s offset 0,-0.6\n", gnuplotString(spec.differences[i].caption).c_str());
            if (i > 0) std::fprintf(f, "unset colorbox\n");
            std::fprintf(f, "plot %s binary array=(%d,%d) format='%%float' flipy with image\n",
                         differenceFiles[i].c_str(), w, h);
          }
        }
        std::fprintf(f, "unset multiplot\n");
      },
      {png.filename().string()}, "the comparison figure " + png.filename().string());
  return true;
}

}  // namespace tallow::app
