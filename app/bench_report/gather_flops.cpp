#include "app/bench_report/gather_flops.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "app/bench_report/counted_real.h"
#include "gpu/glsl_shared.h"  // TALLOW_FN and GLM's GLSL vocabulary; no OpenGL

static_assert(sizeof(unsigned) == 4, "GLSL uint literals (123u) must be 32-bit unsigned int in C++");

// The shared files once with the counting scalar and once in plain float, as sss/maps/
// radiosity_estimator.cpp compiles them: the plain one checks that counting changed no value.
namespace tallow::flops::counted {
using uint = std::uint32_t;
using real = CountedReal;
#include "gpu/glsl_real_types.inc"
#include "sss/bssrdf/bssrdf_models.inc"
#include "shaders/maps/estimator.glsl"
#include "app/bench_report/gather_sample.inc"
}  // namespace tallow::flops::counted

namespace tallow::flops::plain {
using uint = std::uint32_t;
using real = float;
#include "gpu/glsl_real_types.inc"
#include "sss/bssrdf/bssrdf_models.inc"
#include "shaders/maps/estimator.glsl"
#include "app/bench_report/gather_sample.inc"
}  // namespace tallow::flops::plain

namespace tallow::flops {

GatherFlops countGatherFlops(const sss::Material& material, sss::BssrdfModel model, int samplesPerBand) {
  if (samplesPerBand < 1) throw std::invalid_argument("countGatherFlops: samplesPerBand must be at least 1");
  const int modelId = static_cast<int>(model);
  static_assert(static_cast<int>(sss::BssrdfModel::Directional) == plain::BSSRDF_MODEL_DIRECTIONAL);
  // Per band and texel, outside the sample loop in gather.glsl: not part of a sample's count.
  const auto coefficients = [&](auto make, int band) {
    return make(material.sigma_a[band], material.sigma_s[band], material.g[band], material.eta);
  };
  const auto countedK = [](auto&&... a) { return counted::bssrdfCoefficients(a...); };
  const auto plainK = [](auto&&... a) { return plain::bssrdfCoefficients(a...); };
  const auto kc0 = coefficients(countedK, 0), kc1 = coefficients(countedK, 1), kc2 = coefficients(countedK, 2);
  const auto kp0 = coefficients(plainK, 0), kp1 = coefficients(plainK, 1), kp2 = coefficients(plainK, 2);
  const counted::real3 sigmaTrC(counted::sssSamplingSigmaTr(kc0), counted::sssSamplingSigmaTr(kc1),
                                counted::sssSamplingSigmaTr(kc2));
  const plain::real3 sigmaTrP(plain::sssSamplingSigmaTr(kp0), plain::sssSamplingSigmaTr(kp1),
                              plain::sssSamplingSigmaTr(kp2));
  GatherFlops out;
  out.flopsSharedMin = ~std::uint64_t{0};
  double add = 0, mul = 0, div = 0, special = 0, other = 0, flops = 0;
  const auto n = static_cast<std::uint32_t>(samplesPerBand);
  for (std::uint32_t j = 0; j < n; ++j) {
    reset();
    const counted::real3 value = counted::gatherPlaneSample(modelId, kc0, kc1, kc2, sigmaTrC, j, n);
    const OpCounts c = counts();
    const plain::real3 expected = plain::gatherPlaneSample(modelId, kp0, kp1, kp2, sigmaTrP, j, n);
    for (int band = 0; band < 3; ++band)
      out.maxValueDifference =
          std::max(out.maxValueDifference, std::abs(double(value[band].value()) - double(expected[band])));
    add += double(c.add), mul += double(c.mul), div += double(c.div), special += double(c.special);
    other += double(c.other), flops += double(c.flops());
    out.flopsSharedMin = std::min(out.flopsSharedMin, c.flops());
    out.flopsSharedMax = std::max(out.flopsSharedMax, c.flops());
    ++out.samples;
  }
  // Per sample and band: the shared sample's count over its three bands.
  const double perBand = 3.0 * out.samples;
  out.flopsPerSharedSample = flops / out.samples;
  out.flopsMean = flops / perBand, out.addMean = add / perBand, out.mulMean = mul / perBand;
  out.divMean = div / perBand, out.specialMean = special / perBand, out.otherMean = other / perBand;
  return out;
}

}  // namespace tallow::flops
