#pragma once
// SSLPV on the flat slab written independently of the GPU passes (tests only). The slab is uniform
// across x and z, so every cell of a layer holds the same coefficients and one propagation step
// is, per layer i (0 at the bottom, layers − 1 at the lit top),
//   c'_i = Σ_{±x,±z} M_s a(c_i) + M_{+y} a(c_{i+1}) + M_{−y} a(c_{i−1}),  a(c) = scatter(e^{−σ_t ΔX} c),
// with no cells above the top layer or below the bottom (vacuum). The top layer's cells receive the
// injected flux in a cosine lobe straight down (Eq. 1 at normal incidence).
#include <glm/glm.hpp>

#include <cmath>
#include <vector>

#include "sss/peers/sslpv_math.h"

namespace tallow::test {

struct SlabRecursion {
  glm::dvec4 top{0.0};  ///< the top layer's accumulation grid coefficients (steps skip + 1 … steps)
  double escaped = 0.0; ///< flux the top layer sent to the vacuum above, summed over all steps [W]
};

/// One colour band: `flux` [W] injected per top cell of `cellMm` mm, `layers` layers.
inline SlabRecursion slabRecursion(float sigmaA, float sigmaS, float g, double flux, double cellMm, int layers,
                                   int steps, int skip) {
  namespace sh = sss::sslpv_glsl;
  const auto M = sss::sslpvPropagationMatrices();
  const float cell = static_cast<float>(cellMm);
  const float st = sh::sslpvGridExtinction(sigmaA, sigmaS, g, cell);
  const float sp = sh::sslpvScatteringFraction(sigmaS, cell);
  std::vector<glm::dvec4> c(static_cast<std::size_t>(layers), glm::dvec4(0.0));
  c.back() = flux * glm::dvec4(sh::sslpvCosineLobe(glm::vec3(0, -1, 0)));
  SlabRecursion out;
  const double twoSqrtPi = 2.0 * std::sqrt(3.14159265358979323846);
  for (int step = 1; step <= steps; ++step) {
    std::vector<glm::dvec4> leaving(c.size()), next(c.size(), glm::dvec4(0.0));
    for (std::size_t i = 0; i < c.size(); ++i)
      leaving[i] = glm::dvec4(sh::sslpvAttenuateAndScatter(glm::vec4(c[i]), st, sp, g, cell));
    for (int i = 0; i < layers; ++i) {
      glm::dvec4 sum(0.0);
      for (int s : {0, 1, 4, 5}) sum += glm::dmat4(M[static_cast<std::size_t>(s)]) * leaving[static_cast<std::size_t>(i)];
      if (i + 1 < layers) sum += glm::dmat4(M[2]) * leaving[static_cast<std::size_t>(i + 1)];  // source at +y
      if (i > 0) sum += glm::dmat4(M[3]) * leaving[static_cast<std::size_t>(i - 1)];           // source at −y
      next[static_cast<std::size_t>(i)] = sum;
    }
    // What the top layer sends to the cell above it (the destination has the source at −y).
    out.escaped += twoSqrtPi * (glm::dmat4(M[3]) * leaving.back())[0];
    c = next;
    if (step > skip) out.top += c.back();
  }
  return out;
}

}  // namespace tallow::test
