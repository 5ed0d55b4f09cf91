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

ImageError imageError(const Image& image, const Image& reference, const Image& mask) {
  checkSizes(image, reference, mask);
  double sumErr2 = 0.0, sumRef2 = 0.0, maxErr = 0.0, sumImage = 0.0, sumRef = 0.0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < mask.pixels.size(); ++i) {
    if (!isObject(mask.pixels[i])) continue;
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
  e.rmse = std::sqrt(sumErr2 / double(n));
  e.maxError = maxErr;
  e.meanRatio = sumRef > 0.0 ? sumImage / sumRef : (sumImage > 0.0 ? std::numeric_limits<double>::infinity() : 1.0);
  const double refRms = std::sqrt(sumRef2 / double(n));
  e.relRmse = refRms > 0.0 ? e.rmse / refRms : (e.rmse > 0.0 ? std::numeric_limits<double>::infinity() : 0.0);
  return e;
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
