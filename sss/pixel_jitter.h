#pragma once
// Sub-pixel sample positions shared by the GPU's still average (render.aa: the camera pass
// jittered frame by frame, sss/still_average.h) and the CPU reference's box filter (one position
// per pass), so that the two integrate the same pixel footprint.
#include <glm/glm.hpp>

namespace tallow::sss {

/// Radical inverse of k in base b (van der Corput): the digits of k mirrored about the point.
inline double radicalInverse(unsigned k, unsigned base) {
  double inverse = 1.0 / base, scale = inverse, value = 0.0;
  for (; k > 0; k /= base, scale *= inverse) value += static_cast<double>(k % base) * scale;
  return value;
}

/// Offset of sample k from the pixel centre, in pixels, in [−½, ½)²: the Halton (2, 3) point k
/// (Halton 1960) rotated by ½ (Cranley and Patterson 1976), so that k = 0 is the centre itself and
/// the first n points of the sequence cover the pixel with low discrepancy for every n.
inline glm::dvec2 pixelJitter(unsigned k) {
  const auto centred = [](double u) { return u + 0.5 >= 1.0 ? u - 0.5 : u + 0.5; };  // frac(u + ½)
  return {centred(radicalInverse(k, 2)) - 0.5, centred(radicalInverse(k, 3)) - 0.5};
}

}  // namespace tallow::sss
