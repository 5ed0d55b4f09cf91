#pragma once
// The melting candle (CandleField) evaluated on the GPU (issue 16, point 2): its signed distance
// and analytic gradient from the candle's shape at t as uniforms (shaders/fields/candle.glsl, the
// lines CandleField::value / gradient evaluate in C++). fill() writes a GpuDualContouring's lattice
// with a compute shader (shaders/fields/lattice.comp with FIELD_CANDLE) and sets the uniforms of its
// analytic vertex normals: per frame the CPU computes the shape (candleShapeAt: the heights, the
// cup and a few drip spheres) and sets uniforms; no lattice is sampled on the CPU, nothing is
// uploaded, nothing is read back. The blob's counterpart is GpuBlobField.
#include "geometry/candle_field.h"
#include "geometry/gpu_dual_contouring.h"
#include "geometry/grid_sampler.h"
#include "gpu/program.h"
#include "gpu/shader_library.h"

namespace tallow::geometry {

class GpuCandleField {
 public:
  /// Builds the lattice program. Needs a current GL 4.5 context.
  explicit GpuCandleField(const gpu::ShaderLibrary& library);

  /// Fills `dc`'s lattice with `candle` at `frame`'s samples (frame.values unused: origin and cell
  /// size, frame.n == dc's n) and, when dc takes its normals from the candle
  /// (NormalSource::CandleGradient), sets them to this candle. No stall, no read-back.
  void fill(GpuDualContouring& dc, const CandleField& candle, const SampledLattice& frame);

  /// Sets the uniforms of shaders/fields/candle_uniforms.glsl on `program` to `candle`.
  static void setUniforms(gpu::Program& program, const CandleField& candle);

 private:
  gpu::Program lattice_;
};

}  // namespace tallow::geometry
