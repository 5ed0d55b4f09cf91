#pragma once
// Captioned pictures of a comparison, for people (bench rows, `tallow compare`, docs/RESULTS.md):
// tone-mapped images side by side, each under its caption, and below them their differences in
// false colour — |Δ| per pixel relative to the RMS radiance of the reference over the compared
// pixels, the normalisation of the bench's relative RMSE, so the colours read as that metric does —
// on one perceptual scale (dark violet → yellow) with a labelled colour bar. Small images are
// enlarged pixel for pixel so that 64×48 renders stay legible. Drawn by gnuplot into one PNG.
#include <filesystem>
#include <string>
#include <vector>

#include "gpu/image.h"
#include "gpu/tonemap.h"

namespace tallow::app {

struct FigureImage {
  const gpu::Image* image = nullptr;
  std::string caption;
};

struct FigureDifference {
  const gpu::Image* image = nullptr;
  const gpu::Image* reference = nullptr;
  std::string caption;
  int column = 0;  ///< the column (of the images above) it stands under
};

struct FigureSpec {
  std::string title;
  std::vector<FigureImage> images;            ///< the first row, all of one size
  std::vector<FigureDifference> differences;  ///< the second row, sharing one colour scale
  /// The compared pixels (alpha ≥ gpu::kObjectMaskAlpha, as `tallow reference`'s standard-error
  /// image marks them); null: every pixel. Pixels outside are left white.
  const gpu::Image* mask = nullptr;
  gpu::ToneMapSettings toneMap;
  /// Top of the colour scale as a fraction (0.2: 20%); 0: chosen from the differences (their 99th
  /// percentile rounded up to 1, 2 or 5 × 10^k), so that a few outliers do not darken the rest.
  double scale = 0.0;
  /// The colour bar's label: what the differences are relative to.
  std::string scaleLabel = "|Δ| / RMS of the reference";
};

/// |image − reference| per pixel (√(Δr² + Δg² + Δb²)) / √(mean over the mask of r² + g² + b² of the
/// reference), top row first; NaN outside the mask. Throws std::invalid_argument when sizes differ.
std::vector<float> relativeDifference(const gpu::Image& image, const gpu::Image& reference, const gpu::Image* mask);

/// The smallest 1, 2 or 5 × 10^k at or above the `quantile` of the finite values, within float
/// rounding (1 when none is positive).
double niceScale(std::vector<float> values, double quantile = 0.99);

/// Draws `spec` into `png` (atomically). Returns false, writing nothing, when gnuplot is not
/// installed; throws std::runtime_error when gnuplot fails, std::invalid_argument on sizes that differ.
bool writeComparisonFigure(const std::filesystem::path& png, const FigureSpec& spec);

}  // namespace tallow::app
