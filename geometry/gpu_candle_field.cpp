#include "geometry/gpu_candle_field.h"

#include <array>
#include <iterator>
#include <vector>
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
  program.set("uCandle.poolY", f(c.poolY));
  program.set("uCandle.poolRadius", f(c.poolRadius));
  program.set("uCandle.poolDepth", f(c.poolDepth));
  program.set("uCandle.wickRadius", f(c.wickRadius));
  program.set("uCandle.wickBottom", f(c.wickBottom));
  program.set("uCandle.wickTop", f(c.wickTop));
  program.set("uCandle.flameY", f(c.flameY));
  program.set("uCandle.smoothing", f(c.smoothing));
  program.set("uCandle.band", f(c.band));
  program.set("uCandle.reach", f(c.reach));
  program.set("uCandle.low", f(c.low));
  program.set("uCandle.high", f(c.high));
  program.set("uCandle.profileCount", c.profileCount);
  program.set("uCandle.notchCount", c.notchCount);
  program.set("uCandle.dripClipY", f(c.dripClipY));
  program.set("uCandle.dripCount", c.dripCount);
  program.set("uCandle.puddleCount", c.puddleCount);
  program.set("uCandle.puddleThickness", f(c.puddleThickness));
  // The arrays of four-vectors, converted from double.
  const auto set = [&](const char* name, const auto& values) {
    std::vector<glm::vec4> floats(std::begin(values), std::end(values));
    program.set(name, floats.data(), static_cast<int>(floats.size()));
  };
  set("uCandle.profile", c.profile);
  set("uCandle.notch", c.notch);
  set("uCandle.drip", c.drip);
  set("uCandle.dripBound", c.dripBound);
  set("uCandle.puddle", c.puddle);
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
