#pragma once
// The bench's speed-against-error plot (speed_error.png, redrawn by hand from bench.gp): one colour
// and marker per method (the same for a method in every bench), each point labelled with its swept
// values where they tell rows apart, labels placed so that they overlap neither each other nor the
// markers (a thin leader line when one had to move away), and a dashed line at each reference's
// own relative error ε: below it, a row's error is the reference's noise, not the method's.
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace tallow::app {

/// A rectangle in pixels, y up (gnuplot's screen coordinates times the terminal size).
struct PixelRect {
  double x0 = 0.0, y0 = 0.0, x1 = 0.0, y1 = 0.0;
  bool overlaps(const PixelRect& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
  bool inside(const PixelRect& o) const { return x0 >= o.x0 && x1 <= o.x1 && y0 >= o.y0 && y1 <= o.y1; }
};

struct LabelPlacement {
  bool placed = false;
  PixelRect box;        ///< where the text goes
  bool leader = false;  ///< away from its point: draw a line from the point to it
};

/// Places one label of size `sizes[i]` (w, h pixels) next to each anchor (a marker of radius
/// `markerRadius` pixels) inside `area`, greedily in order: the first of eight directions around the
/// point, on rings of growing distance, whose box stays in `area` and overlaps no marker, no label
/// placed before and none of `reserved`. A label with no such place is left out (placed = false).
std::vector<LabelPlacement> placeLabels(const std::vector<glm::dvec2>& anchors, const std::vector<glm::dvec2>& sizes,
                                        const PixelRect& area, double markerRadius,
                                        const std::vector<PixelRect>& reserved = {});

struct SpeedErrorPoint {
  std::string method;
  int style = 0;      ///< colour and marker index (the method's place among the registry's choices)
  std::string label;  ///< the swept values; empty: none
  double ms = 0.0;    ///< median wall time per frame
  double error = 0.0; ///< relative RMSE of the last frame
};

struct ReferenceLine {
  double error = 0.0;  ///< the reference's relative standard error ε
  std::string label;   ///< "reference ε" and, with several references, their settings
};

/// Draws `folder`/speed_error.png through gnuplot and keeps its script, speed_error.gp (the data
/// inline), to redraw it by hand in that folder (app/commands/gnuplot.h: nothing without gnuplot;
/// std::runtime_error when it fails).
void writeSpeedErrorPlot(const std::filesystem::path& folder, const std::string& title,
                         const std::vector<SpeedErrorPoint>& points, const std::vector<ReferenceLine>& references);

}  // namespace tallow::app
