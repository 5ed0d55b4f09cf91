#pragma once
// The bench's error metric (DESIGN "Measuring"; docs/commands.md, `tallow bench`): per object pixel
// p, e_p = √(Δr² + Δg² + Δb²) with Δ = image − reference; RMSE = √(mean_p e_p²); relative RMSE =
// RMSE / √(mean_p (r² + g² + b²) of the reference), the normalisation of the reference's own error
// statistic (sss::kReferenceErrorStatistic), so the two compare directly; max = max_p e_p.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "gpu/image.h"

namespace tallow::gpu {

/// Object pixels are those whose mask alpha is at least this (`tallow reference`'s standard-error
/// image has alpha 1 where the camera ray hits a translucent object and 0 elsewhere).
inline constexpr float kObjectMaskAlpha = 0.5f;

struct ImageError {
  /// NaN when a compared pixel of either image is not finite (and such pixels were not left out):
  /// the error is then undefined, never 0.
  double rmse = 0.0;
  double relRmse = 0.0;  ///< RMSE / RMS of the reference (infinite for a black reference and RMSE > 0)
  double maxError = 0.0;
  /// Σ_p Σ_c image / Σ_p Σ_c reference: the bias of the mean, which the RMSE mixes with noise
  /// (infinite for a black reference with a non-black image; 1 when both are black).
  double meanRatio = 1.0;
  std::size_t pixels = 0;  ///< object pixels compared
  /// Object pixels with a NaN or infinite channel, in the image and in the reference.
  std::size_t nonFiniteImage = 0, nonFiniteReference = 0;
  /// Object pixels left out because one of the two is not finite (ImageErrorOptions::skipNonFinite).
  std::size_t skippedNonFinite = 0;
  bool finite() const { return nonFiniteImage == 0 && nonFiniteReference == 0; }
};

struct ImageErrorOptions {
  /// Leave out (and count) the object pixels where either image is not finite, instead of making
  /// every metric NaN.
  bool skipNonFinite = false;
};

/// Whether all three channels of a pixel are finite (alpha is not looked at).
bool finitePixel(const glm::vec4& p);
/// Pixels of `image` with a NaN or infinite colour channel, over the object pixels of `mask` (all
/// pixels when `mask` is null).
std::size_t nonFinitePixels(const Image& image, const Image* mask = nullptr);

/// Pixels of `mask` with alpha ≥ kObjectMaskAlpha.
std::size_t objectPixels(const Image& mask);

/// The metric above over the object pixels of `mask`. Throws std::invalid_argument with one line
/// when the three sizes differ or the mask has no object pixel. Non-finite pixels are counted;
/// with any of them compared, rmse, relRmse, maxError and meanRatio are NaN.
ImageError imageError(const Image& image, const Image& reference, const Image& mask,
                      const ImageErrorOptions& options = {});

/// Temporal stability (flicker): Σ_p Σ_c |now − before| / Σ_p Σ_c now over the pixels where `mask`
/// is non-zero (one byte per pixel, top row first as Image), i.e. the mean absolute frame-to-frame
/// change relative to the mean radiance. 0 for identical frames; throws std::invalid_argument on
/// mismatched sizes; NaN when the masked pixels of `now` are all black.
double relativeChange(const Image& now, const Image& before, const std::vector<std::uint8_t>& mask);

/// The error over the upper and the lower half of the object's rows (issue 17's per-region bias:
/// compare meanRatio of each). The object's rows [top, bottom] of `mask` split at (top + bottom + 1)/2:
/// the upper half above that row, the lower half from it down. std::nullopt when the object spans
/// fewer than two rows; throws as imageError on mismatched sizes or an empty mask.
struct HalvesError {
  ImageError upper, lower;
};
std::optional<HalvesError> imageErrorByHalf(const Image& image, const Image& reference, const Image& mask,
                                            const ImageErrorOptions& options = {});

/// Fireflies (issue 17): object pixels of `image` with a channel above `factor` times the median of
/// that channel over the object pixels of its 5×5 neighbourhood (itself included; the upper median
/// of an even count). Throws
/// std::invalid_argument when the sizes differ.
inline constexpr float kFireflyFactor = 4.0f;
std::size_t fireflyCount(const Image& image, const Image& mask, float factor = kFireflyFactor);

/// One firefly: its pixel, the first channel above the threshold, and that channel's value over its
/// neighbourhood's median (> factor; infinite where the median is 0).
struct Firefly {
  int x = 0, y = 0, channel = 0;
  float overMedian = 0.0f;
};
/// The pixels fireflyCount counts, in row order (top row first), with the same throws.
std::vector<Firefly> fireflies(const Image& image, const Image& mask, float factor = kFireflyFactor);
/// Channel c of pixel (x, y) over the median of that channel in its 5×5 neighbourhood's object
/// pixels, the statistic fireflies() thresholds (infinite where that median is 0 and the value is not;
/// NaN where both are 0). Lets a caller ask how close another image's pixel came to being one.
float fireflyRatio(const Image& image, const Image& mask, int x, int y, int c);

/// |Δ| per band, alpha e_p (both 0 outside the mask), for pictures. Same errors as imageError.
Image differenceImage(const Image& image, const Image& reference, const Image& mask);

}  // namespace tallow::gpu
