#include "geometry/gpu_candle_field.h"

#include <array>
#include <stdexcept>
#include <string>

namespace tallow::geometry {

GpuCandleField::GpuCandleField(const gpu::ShaderLibrary& library)
    : lattice_(library, {{{GL_COMPUTE_SHADER, "fields/lattice.comp"}}, {"FIELD_CANDLE"}}) {}

void GpuCandleField::setUniforms(gpu::Program& program, const CandleField& candle) {
  const candle_f64::CandleShape& c = candle.shape();
  const auto f = [](double v) { return static_cast<float>(v); };
  program.set("uCandle.radius", f(c.radius));
  program.set("uCandle.height", f(c.height));
  program.set("uCandle.cupRadius", f(c.cupRadius));
  program.set("uCandle.cupDepth", f(c.cupDepth));
  program.set("uCandle.bowlRadius", f(c.bowlRadius));
  program.set("uCandle.bowlCentreY", f(c.bowlCentreY));
  program.set("uCandle.wickRadius", f(c.wickRadius));
  program.set("uCandle.wickBottom", f(c.wickBottom));
  program.set("uCandle.wickTop", f(c.wickTop));
  program.set("uCandle.flameY", f(c.flameY));
  program.set("uCandle.smoothing", f(c.smoothing));
  program.set("uCandle.band", f(c.band));
  program.set("uCandle.reach", f(c.reach));
  program.set("uCandle.low", f(c.low));
  program.set("uCandle.high", f(c.high));
  program.set("uCandle.dripCount", c.dripCount);
  std::array<glm::vec3, candle_f64::CANDLE_MAX_SPHERES> centres{};
  for (int i = 0; i < candle_f64::CANDLE_MAX_SPHERES; ++i) {
    centres[static_cast<std::size_t>(i)] = glm::vec3(c.dripCentre[i]);
    program.set("uCandle.dripRadius[" + std::to_string(i) + "]", f(c.dripRadius[i]));
  }
  program.set("uCandle.dripCentre", centres.data(), candle_f64::CANDLE_MAX_SPHERES);
}

void GpuCandleField::fill(GpuDualContouring& dc, const CandleField& candle, const SampledLattice& frame) {
  if (frame.n != dc.samplesPerAxis())
    throw std::runtime_error("GpuCandleField::fill: lattice has " + std::to_string(frame.n) +
                             " samples per axis, the extractor " + std::to_string(dc.samplesPerAxis()));
  setUniforms(lattice_, candle);
  dc.fillOnGpu(lattice_, frame.origin, frame.cellSize);
  if (dc.normalSource() == NormalSource::CandleGradient) setUniforms(dc.normalProgram(), candle);
}

}  // namespace tallow::geometry
