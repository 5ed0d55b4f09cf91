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
  GatherFlops out;
  out.flopsMin = ~std::uint64_t{0};
  double add = 0, mul = 0, div = 0, special = 0, other = 0, flops = 0;
  for (int band = 0; band < 3; ++band) {
    // Per band and texel, outside the sample loop in gather.glsl: not part of a sample's count.
    const auto kc = counted::bssrdfCoefficients(material.sigma_a[band], material.sigma_s[band], material.g[band],
                                                material.eta);
    const auto sigmaTrC = counted::sssSamplingSigmaTr(kc);
    const auto kp = plain::bssrdfCoefficients(material.sigma_a[band], material.sigma_s[band], material.g[band],
                                              material.eta);
    const float sigmaTrP = plain::sssSamplingSigmaTr(kp);
    for (int j = 0; j < samplesPerBand; ++j) {
      const auto b = static_cast<std::uint32_t>(band), s = static_cast<std::uint32_t>(j);
      reset();
      const counted::real value = counted::gatherPlaneSample(modelId, kc, sigmaTrC, b, s);
      const OpCounts c = counts();
      const float expected = plain::gatherPlaneSample(modelId, kp, sigmaTrP, b, s);
      out.maxValueDifference = std::max(out.maxValueDifference, std::abs(double(value.value()) - double(expected)));
      add += double(c.add), mul += double(c.mul), div += double(c.div), special += double(c.special);
      other += double(c.other), flops += double(c.flops());
      out.flopsMin = std::min(out.flopsMin, c.flops());
      out.flopsMax = std::max(out.flopsMax, c.flops());
      ++out.samples;
    }
  }
  const double n = out.samples;
  out.flopsMean = flops / n, out.addMean = add / n, out.mulMean = mul / n, out.divMean = div / n;
  out.specialMean = special / n, out.otherMean = other / n;
  return out;
}

}  // namespace tallow::flops
