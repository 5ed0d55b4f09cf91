#include "app/bench_report/gather_flops.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "gpu/glsl_shared.h"  // TALLOW_FN and GLM's GLSL vocabulary; no OpenGL
#include "sss/render_settings.h"

static_assert(sizeof(unsigned) == 4, "GLSL uint literals (123u) must be 32-bit unsigned int in C++");

// The shared files once with the counting scalar and once in plain float, as sss/maps/
// radiosity_estimator.cpp compiles them: the plain one checks that counting changed no value.
namespace tallow::flops::counted {
using uint = std::uint32_t;
using real = CountedReal;
#include "gpu/glsl_real_types.inc"
#include "sss/bssrdf/bssrdf_models.inc"
#include "shaders/maps/estimator.glsl"
#include "app/bench_report/gather_flops_scene.inc"
}  // namespace tallow::flops::counted

namespace tallow::flops::plain {
using uint = std::uint32_t;
using real = float;
#include "gpu/glsl_real_types.inc"
#include "sss/bssrdf/bssrdf_models.inc"
#include "shaders/maps/estimator.glsl"
#include "app/bench_report/gather_flops_scene.inc"
}  // namespace tallow::flops::plain

namespace tallow::flops {

std::vector<OpCounts>& marks() {
  thread_local std::vector<OpCounts> m;
  return m;
}

namespace {

OpCounts minus(const OpCounts& a, const OpCounts& b) {
  return {a.add - b.add, a.mul - b.mul, a.div - b.div, a.special - b.special, a.other - b.other};
}

/// One loop counted: the samples are what lies between successive look-ups of the last N marks
/// (each: the rest of sample j and the draw of sample j + 1), the texel's share the remainder.
LoopFlops countLoop(int kind, int model, const sss::Material& m, int samples, float share, double& maxDifference) {
  reset();
  marks().clear();
  const counted::real3 value = counted::sssFlopsGather(kind, model, m, samples, share);
  const OpCounts total = counts();
  const std::vector<OpCounts> at = marks();
  const plain::real3 expected = plain::sssFlopsGather(kind, model, m, samples, share);
  for (int band = 0; band < 3; ++band)
    maxDifference = std::max(maxDifference, std::abs(double(value[band].value()) - double(expected[band])));
  if (at.size() < static_cast<std::size_t>(samples))
    throw std::logic_error("countGatherFlops: fewer look-ups than samples");
  LoopFlops out;
  out.flopsSharedMin = ~std::uint64_t{0};
  double add = 0, mul = 0, div = 0, special = 0, other = 0, flops = 0;
  for (std::size_t i = at.size() - static_cast<std::size_t>(samples) + 1; i < at.size(); ++i) {
    const OpCounts c = minus(at[i], at[i - 1]);
    add += double(c.add), mul += double(c.mul), div += double(c.div), special += double(c.special);
    other += double(c.other), flops += double(c.flops());
    out.flopsSharedMin = std::min(out.flopsSharedMin, c.flops());
    out.flopsSharedMax = std::max(out.flopsSharedMax, c.flops());
    ++out.samples;
  }
  const double perBand = 3.0 * out.samples;
  out.flopsPerSharedSample = flops / out.samples;
  out.flopsMean = flops / perBand, out.addMean = add / perBand, out.mulMean = mul / perBand;
  out.divMean = div / perBand, out.specialMean = special / perBand, out.otherMean = other / perBand;
  out.flopsPerTexel = double(total.flops()) - samples * out.flopsPerSharedSample;
  return out;
}

}  // namespace

GatherFlops countGatherFlops(const sss::Material& material, sss::BssrdfModel model, int samplesPerBand) {
  if (samplesPerBand < 2) throw std::invalid_argument("countGatherFlops: samplesPerBand must be at least 2");
  const int modelId = static_cast<int>(model);
  static_assert(static_cast<int>(sss::BssrdfModel::Directional) == plain::BSSRDF_MODEL_DIRECTIONAL);
  const float share = sss::RenderSettings{}.sss.pointShare;
  GatherFlops out;
  out.directional = countLoop(0, modelId, material, samplesPerBand, share, out.maxValueDifference);
  out.point = countLoop(1, modelId, material, samplesPerBand, share, out.maxValueDifference);
  return out;
}

}  // namespace tallow::flops
