#include "gpu/image_error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace tallow::gpu {
namespace {

std::string sizeText(const Image& i) { return std::to_string(i.width) + "x" + std::to_string(i.height); }

void checkSizes(const Image& image, const Image& reference, const Image& mask) {
  if (image.width != reference.width || image.height != reference.height)
    throw std::invalid_argument("image error: the image is " + sizeText(image) + " but the reference is " +
                                sizeText(reference));
  if (mask.width != reference.width || mask.height != reference.height)
    throw std::invalid_argument("image error: the object mask is " + sizeText(mask) + " but the reference is " +
                                sizeText(reference));
  if (objectPixels(mask) == 0) throw std::invalid_argument("image error: the object mask has no object pixel");
}

bool isObject(const glm::vec4& m) { return m.a >= kObjectMaskAlpha; }

}  // namespace

double relativeChange(const Image& now, const Image& before, const std::vector<std::uint8_t>& mask) {
  if (now.width != before.width || now.height != before.height || mask.size() != now.pixels.size())
    throw std::invalid_argument("relative change: the frames are " + sizeText(now) + " and " + sizeText(before) +
                                " with a mask of " + std::to_string(mask.size()) + " pixels");
  double change = 0.0, total = 0.0;
  for (std::size_t i = 0; i < mask.size(); ++i) {
    if (!mask[i]) continue;
    const glm::dvec3 a(now.pixels[i]), b(before.pixels[i]);
    const glm::dvec3 d = glm::abs(a - b);
    change += d.x + d.y + d.z;
    total += a.x + a.y + a.z;
  }
  if (total <= 0.0) return change > 0.0 ? std::numeric_limits<double>::infinity() : std::numeric_limits<double>::quiet_NaN();
  return change / total;
}

std::size_t objectPixels(const Image& mask) {
  return static_cast<std::size_t>(std::count_if(mask.pixels.begin(), mask.pixels.end(), isObject));
}

bool finitePixel(const glm::vec4& p) { return std::isfinite(p.r) && std::isfinite(p.g) && std::isfinite(p.b); }

std::size_t nonFinitePixels(const Image& image, const Image* mask) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < image.pixels.size(); ++i)
    if ((!mask || isObject(mask->pixels[i])) && !finitePixel(image.pixels[i])) ++n;
  return n;
}

ImageError imageError(const Image& image, const Image& reference, const Image& mask, const ImageErrorOptions& options) {
  checkSizes(image, reference, mask);
  double sumErr2 = 0.0, sumRef2 = 0.0, maxErr = 0.0, sumImage = 0.0, sumRef = 0.0;
  std::size_t n = 0, nonFiniteImage = 0, nonFiniteReference = 0, skipped = 0;
  for (std::size_t i = 0; i < mask.pixels.size(); ++i) {
    if (!isObject(mask.pixels[i])) continue;
    const bool imageFinite = finitePixel(image.pixels[i]), referenceFinite = finitePixel(reference.pixels[i]);
    nonFiniteImage += !imageFinite;
    nonFiniteReference += !referenceFinite;
    if (options.skipNonFinite && !(imageFinite && referenceFinite)) {
      ++skipped;
      continue;
    }
    const glm::dvec3 r(reference.pixels[i]);
    const glm::dvec3 d = glm::dvec3(image.pixels[i]) - r;
    const double e2 = glm::dot(d, d);
    sumErr2 += e2;
    sumRef2 += glm::dot(r, r);
    sumImage += double(image.pixels[i].r) + image.pixels[i].g + image.pixels[i].b;
    sumRef += r.r + r.g + r.b;
    maxErr = std::max(maxErr, std::sqrt(e2));
    ++n;
  }
  ImageError e;
  e.pixels = n;
  e.nonFiniteImage = nonFiniteImage;
  e.nonFiniteReference = nonFiniteReference;
  e.skippedNonFinite = skipped;
  // A NaN compared is an undefined error, not a small one (std::max and `> 0` would hide it); so is
  // an error over no pixel, when every object pixel was left out.
  if ((skipped == 0 && !e.finite()) || n == 0) {
    constexpr double kUndefined = std::numeric_limits<double>::quiet_NaN();
    e.rmse = e.relRmse = e.maxError = e.meanRatio = kUndefined;
    return e;
  }
  e.rmse = std::sqrt(sumErr2 / double(n));
  e.maxError = maxErr;
  e.meanRatio = sumRef > 0.0 ? sumImage / sumRef : (sumImage > 0.0 ? std::numeric_limits<double>::infinity() : 1.0);
  const double refRms = std::sqrt(sumRef2 / double(n));
  e.relRmse = refRms > 0.0 ? e.rmse / refRms : (e.rmse > 0.0 ? std::numeric_limits<double>::infinity() : 0.0);
  return e;
}

std::optional<HalvesError> imageErrorByHalf(const Image& image, const Image& reference, const Image& mask,
                                            const ImageErrorOptions& options) {
  checkSizes(image, reference, mask);
  int top = mask.height, bottom = -1;
  for (int y = 0; y < mask.height; ++y)
    for (int x = 0; x < mask.width; ++x)
      if (isObject(mask.at(x, y))) top = std::min(top, y), bottom = std::max(bottom, y);
  if (bottom <= top) return std::nullopt;
  const int split = (top + bottom + 1) / 2;
  // The mask with the other half's rows cleared; imageError then does the rest.
  const auto half = [&](int from, int to) {
    Image m = mask;
    for (int y = 0; y < m.height; ++y)
      if (y < from || y >= to)
        for (int x = 0; x < m.width; ++x) m.at(x, y).a = 0.0f;
    return imageError(image, reference, m, options);
  };
  return HalvesError{half(top, split), half(split, bottom + 1)};
}

namespace {

/// Median (the upper one of an even count) of channel c over the object pixels of the 5×5 window
/// around (x, y); `window` is scratch space.
float neighbourhoodMedian(const Image& image, const Image& mask, int x, int y, int c, std::vector<float>& window) {
  window.clear();
  for (int v = std::max(0, y - 2); v <= std::min(image.height - 1, y + 2); ++v)
    for (int u = std::max(0, x - 2); u <= std::min(image.width - 1, x + 2); ++u)
      if (isObject(mask.at(u, v))) window.push_back(image.at(u, v)[c]);
  if (window.empty()) return 0.0f;
  const auto middle = window.begin() + static_cast<std::ptrdiff_t>(window.size() / 2);
  std::nth_element(window.begin(), middle, window.end());
  return *middle;
}

void checkFireflySizes(const Image& image, const Image& mask) {
  if (image.width != mask.width || image.height != mask.height)
    throw std::invalid_argument("firefly count: the image is " + sizeText(image) + " but the object mask is " +
                                sizeText(mask));
}

float ratio(float value, float median) {
  if (median != 0.0f) return value / median;
  return value == 0.0f ? std::numeric_limits<float>::quiet_NaN() : std::numeric_limits<float>::infinity();
}

}  // namespace

std::vector<Firefly> fireflies(const Image& image, const Image& mask, float factor) {
  checkFireflySizes(image, mask);
  std::vector<Firefly> found;
  std::vector<float> window;
  window.reserve(25);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      if (!isObject(mask.at(x, y))) continue;
      for (int c = 0; c < 3; ++c) {
        const float median = neighbourhoodMedian(image, mask, x, y, c, window);
        if (image.at(x, y)[c] > factor * median) {
          found.push_back({x, y, c, ratio(image.at(x, y)[c], median)});
          break;
        }
      }
    }
  return found;
}

std::size_t fireflyCount(const Image& image, const Image& mask, float factor) {
  return fireflies(image, mask, factor).size();
}

float fireflyRatio(const Image& image, const Image& mask, int x, int y, int c) {
  checkFireflySizes(image, mask);
  if (x < 0 || y < 0 || x >= image.width || y >= image.height || c < 0 || c > 2)
    throw std::invalid_argument("firefly ratio: pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                                ") channel " + std::to_string(c) + " is outside the " + sizeText(image) + " image");
  std::vector<float> window;
  return ratio(image.at(x, y)[c], neighbourhoodMedian(image, mask, x, y, c, window));
}

Image differenceImage(const Image& image, const Image& reference, const Image& mask) {
  checkSizes(image, reference, mask);
  Image diff(reference.width, reference.height);
  for (std::size_t i = 0; i < mask.pixels.size(); ++i) {
    if (!isObject(mask.pixels[i])) continue;
    const glm::vec3 d = glm::vec3(image.pixels[i]) - glm::vec3(reference.pixels[i]);
    diff.pixels[i] = glm::vec4(glm::abs(d), glm::length(d));
  }
  return diff;
}

}  // namespace tallow::gpu
