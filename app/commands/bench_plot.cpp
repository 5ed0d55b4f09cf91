#include "app/commands/bench_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "app/commands/gnuplot.h"

namespace tallow::app {
namespace {

// The plot's geometry in pixels: the terminal, and margins fixed so that a data point's pixel is
// known here (labels are placed in pixels, then given to gnuplot in screen coordinates).
constexpr int kWidth = 960, kHeight = 600;
constexpr double kLeft = 90, kRight = 220, kBottom = 70, kTop = 50;  ///< the key sits in the right margin
/// pngcairo's ',8' font, measured generously (a label drawn larger than its box could overlap).
constexpr double kCharWidth = 6.2, kLineHeight = 13.0;
constexpr double kMarkerRadius = 6.0;
/// Label candidates: rings of growing distance, eight directions on each.
constexpr int kRings = 6;
constexpr double kRingStep = 14.0, kLabelGap = 3.0;
/// Colours (Okabe and Ito's palette for colour-blind readers, without its yellow, which vanishes on
/// white) and filled markers, one pair per method.
constexpr const char* kColours[] = {"#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000"};
constexpr int kMarkers[] = {7, 5, 9, 13, 11, 15};
/// A y axis spanning more than this ratio is logarithmic.
constexpr double kLogRatio = 5.0;

std::size_t characters(const std::string& text) {
  std::size_t n = 0;
  for (const char c : text) n += (static_cast<unsigned char>(c) & 0xC0) != 0x80;
  return n;
}

/// A data range [lo, hi] padded for the plot: in log10 on a log axis, linearly (from 0) otherwise.
struct Axis {
  bool log = false;
  double lo = 0.0, hi = 1.0;
  double map(double v, double p0, double p1) const {
    const double t = log ? (std::log10(v) - std::log10(lo)) / (std::log10(hi) - std::log10(lo)) : (v - lo) / (hi - lo);
    return p0 + t * (p1 - p0);
  }
};

Axis axisFor(std::vector<double> values, bool forceLog) {
  std::erase_if(values, [](double v) { return !std::isfinite(v) || v <= 0.0; });
  Axis a;
  if (values.empty()) return a;
  const auto [mn, mx] = std::minmax_element(values.begin(), values.end());
  a.log = forceLog || *mx / *mn > kLogRatio;
  if (a.log) {
    const double span = std::max(std::log10(*mx / *mn), 0.3);
    const double pad = 0.12 * span;
    a.lo = std::pow(10.0, std::log10(*mn) - pad - (span == 0.3 ? 0.15 : 0.0));
    a.hi = std::pow(10.0, std::log10(*mx) + pad + (span == 0.3 ? 0.15 : 0.0));
  } else {
    a.lo = 0.0;
    a.hi = *mx * 1.15;
  }
  return a;
}

/// Tics for the error axis as percentages ("5%", "10%"): on a log axis every 1, 2 and 5 × 10^k in
/// range, on a linear one steps of 1, 2 or 5 × 10^k, about five of them.
std::string errorTics(const Axis& a) {
  std::vector<double> tics;
  if (a.log) {
    for (double decade = std::pow(10.0, std::floor(std::log10(a.lo))); decade <= a.hi; decade *= 10.0)
      for (const double m : {1.0, 2.0, 5.0})
        if (m * decade >= a.lo && m * decade <= a.hi) tics.push_back(m * decade);
  } else {
    const double raw = (a.hi - a.lo) / 5.0;
    const double decade = std::pow(10.0, std::floor(std::log10(raw)));
    double step = decade;
    for (const double m : {1.0, 2.0, 5.0, 10.0})
      if (m * decade >= raw) {
        step = m * decade;
        break;
      }
    for (double v = 0.0; v <= a.hi + 1e-12; v += step) tics.push_back(v);
  }
  std::string text = "set ytics (";
  for (std::size_t i = 0; i < tics.size(); ++i) {
    char tic[64];
    // Tic labels are formats to gnuplot: the percent sign doubled.
    std::snprintf(tic, sizeof tic, "%s'%.3g%%%%' %.9g", i ? ", " : "", 100.0 * tics[i], tics[i]);
    text += tic;
  }
  return text + ")\n";
}

}  // namespace

std::vector<LabelPlacement> placeLabels(const std::vector<glm::dvec2>& anchors, const std::vector<glm::dvec2>& sizes,
                                        const PixelRect& area, double markerRadius,
                                        const std::vector<PixelRect>& reserved) {
  std::vector<PixelRect> taken = reserved;
  for (const glm::dvec2& a : anchors)
    taken.push_back({a.x - markerRadius, a.y - markerRadius, a.x + markerRadius, a.y + markerRadius});
  // Right, left, above, below, then the diagonals: the first that fits reads best.
  const glm::dvec2 directions[] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, 1}, {-1, 1}, {1, -1}, {-1, -1}};
  std::vector<LabelPlacement> out(anchors.size());
  for (std::size_t i = 0; i < anchors.size(); ++i) {
    const glm::dvec2 a = anchors[i], s = sizes[i];
    for (int ring = 0; ring < kRings && !out[i].placed; ++ring) {
      const double d = markerRadius + kLabelGap + ring * kRingStep;
      for (const glm::dvec2& dir : directions) {
        // The box's nearest edge (or corner) lies d from the point in that direction.
        const double cx = a.x + dir.x * (d + s.x / 2.0);
        const double cy = a.y + dir.y * (d + s.y / 2.0);
        const PixelRect box{cx - s.x / 2.0, cy - s.y / 2.0, cx + s.x / 2.0, cy + s.y / 2.0};
        if (!box.inside(area)) continue;
        if (std::any_of(taken.begin(), taken.end(), [&](const PixelRect& t) { return box.overlaps(t); })) continue;
        out[i] = {true, box, ring > 0};
        taken.push_back(box);
        break;
      }
    }
  }
  return out;
}

void writeSpeedErrorPlot(const std::filesystem::path& folder, const std::string& title,
                         const std::vector<SpeedErrorPoint>& points, const std::vector<ReferenceLine>& references) {
  std::vector<double> xs, ys;
  for (const SpeedErrorPoint& p : points) {
    xs.push_back(p.ms);
    ys.push_back(p.error);
  }
  for (const ReferenceLine& r : references) ys.push_back(r.error);
  const Axis x = axisFor(xs, /*forceLog=*/true);
  const Axis y = axisFor(ys, false);
  const PixelRect plot{kLeft, kBottom, kWidth - kRight, kHeight - kTop};
  const auto px = [&](double v) { return x.map(v, plot.x0, plot.x1); };
  const auto py = [&](double v) { return y.map(v, plot.y0, plot.y1); };

  // The reference lines' labels first (right end, above the line), then the points'.
  std::vector<PixelRect> reserved;
  std::vector<std::pair<double, double>> referenceLabels;  // left x, centre y in pixels
  for (const ReferenceLine& r : references) {
    if (!(r.error > 0.0) || !std::isfinite(r.error)) continue;
    const double w = kCharWidth * static_cast<double>(characters(r.label)), yy = py(r.error) + kLineHeight / 2.0 + 2.0;
    reserved.push_back({plot.x1 - 4.0 - w, yy - kLineHeight / 2.0, plot.x1 - 4.0, yy + kLineHeight / 2.0});
    referenceLabels.emplace_back(plot.x1 - 4.0 - w, yy);
  }
  std::vector<glm::dvec2> anchors, sizes;
  std::vector<std::size_t> labelled;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (points[i].label.empty() || !(points[i].ms > 0.0) || !std::isfinite(points[i].error)) continue;
    anchors.emplace_back(px(points[i].ms), py(points[i].error));
    sizes.emplace_back(kCharWidth * static_cast<double>(characters(points[i].label)), kLineHeight);
    labelled.push_back(i);
  }
  const std::vector<LabelPlacement> placed = placeLabels(anchors, sizes, plot, kMarkerRadius, reserved);

  // One series per method, in the order first seen.
  std::vector<std::string> methods;
  std::map<std::string, int> styleOf;
  for (const SpeedErrorPoint& p : points)
    if (!styleOf.count(p.method)) {
      methods.push_back(p.method);
      styleOf[p.method] = p.style;
    }
  GnuplotRun(folder).draw(
      [&](std::FILE* f, const std::vector<std::string>& output) {
        std::fprintf(f, "set terminal pngcairo size %d,%d font ',11'\nset output %s\n", kWidth, kHeight, output[0].c_str());
        std::fprintf(f, "set title %s noenhanced\n", gnuplotString(title + ": speed against error").c_str());
        std::fprintf(f, "set lmargin at screen %.6f\nset rmargin at screen %.6f\n", plot.x0 / kWidth, plot.x1 / kWidth);
        std::fprintf(f, "set bmargin at screen %.6f\nset tmargin at screen %.6f\n", plot.y0 / kHeight, plot.y1 / kHeight);
        std::fprintf(f, "set logscale x\nset xrange [%.9g:%.9g]\n", x.lo, x.hi);
        std::fprintf(f, "%sset yrange [%.9g:%.9g]\n", y.log ? "set logscale y\n" : "", y.lo, y.hi);
        std::fprintf(f, "set xlabel 'median wall time per frame [ms]'\nset ylabel 'relative RMSE of the last frame'\n");
        std::fprintf(f, "%sset grid\nset key at screen %.6f,%.6f left top noenhanced\n", errorTics(y).c_str(),
                     (plot.x1 + 15.0) / kWidth, plot.y1 / kHeight);
        for (std::size_t k = 0; k < referenceLabels.size(); ++k) {
          const ReferenceLine& r = references[k];
          std::fprintf(f, "set arrow from graph 0, first %.9g to graph 1, first %.9g nohead dt 2 lw 1.5 lc rgb '#555555'\n",
                       r.error, r.error);
          std::fprintf(f, "set label %s at screen %.6f,%.6f left font ',8' tc rgb '#555555' noenhanced\n",
                       gnuplotString(r.label).c_str(), referenceLabels[k].first / kWidth, referenceLabels[k].second / kHeight);
        }
        for (std::size_t k = 0; k < placed.size(); ++k) {
          if (!placed[k].placed) continue;
          const SpeedErrorPoint& p = points[labelled[k]];
          const PixelRect& b = placed[k].box;
          const char* colour = kColours[static_cast<std::size_t>(p.style) % std::size(kColours)];
          std::fprintf(f, "set label %s at screen %.6f,%.6f left font ',8' tc rgb '%s' noenhanced\n",
                       gnuplotString(p.label).c_str(), b.x0 / kWidth, (b.y0 + b.y1) / 2.0 / kHeight, colour);
          if (placed[k].leader) {
            // From the marker's edge toward the box's nearest point.
            const glm::dvec2 a = anchors[k];
            const glm::dvec2 to{std::clamp(a.x, b.x0, b.x1), std::clamp(a.y, b.y0, b.y1)};
            const glm::dvec2 from = a + glm::normalize(to - a) * kMarkerRadius;
            std::fprintf(f, "set arrow from screen %.6f,%.6f to screen %.6f,%.6f nohead lw 0.6 lc rgb '%s'\n",
                         from.x / kWidth, from.y / kHeight, to.x / kWidth, to.y / kHeight, colour);
          }
        }
        // The data inline (datablocks), so that the kept script redraws without the CSV; comma
        // separated, as the preamble reads data.
        for (std::size_t m = 0; m < methods.size(); ++m) {
          std::fprintf(f, "$m%zu << EOD\n", m);
          for (const SpeedErrorPoint& p : points)
            if (p.method == methods[m]) std::fprintf(f, "%.9g,%.9g\n", p.ms, p.error);
          std::fprintf(f, "EOD\n");
        }
        std::fprintf(f, "plot ");
        for (std::size_t m = 0; m < methods.size(); ++m) {
          const int style = styleOf[methods[m]];
          std::fprintf(f, "%s$m%zu using 1:2 with points pt %d ps 1.5 lc rgb '%s' title %s", m ? ", \\\n     " : "", m,
                       kMarkers[static_cast<std::size_t>(style) % std::size(kMarkers)],
                       kColours[static_cast<std::size_t>(style) % std::size(kColours)], gnuplotString(methods[m]).c_str());
        }
        if (!references.empty())
          std::fprintf(f, ", \\\n     NaN with lines dt 2 lw 1.5 lc rgb '#555555' title 'reference ε'");
        std::fprintf(f, "\n");
      },
      {"speed_error.png"}, "the bench's speed-against-error plot", "speed_error.gp");
}

}  // namespace tallow::app
