#pragma once
// shaders/fields/candle.glsl compiled as C++ in double (gpu/glsl_real_types.inc), the lines the GPU
// evaluates in float: candleShapeAt (the candle at s = t / duration) and candleField (its signed
// distance and gradient at a point). geometry::CandleField evaluates them; geometry::GpuCandleField
// hands a CandleShape to the GPU as uniforms.
#include "gpu/glsl_shared.h"  // TALLOW_FN and GLM's GLSL vocabulary; no OpenGL

namespace tallow::geometry::candle_f64 {
using real = double;
#include "gpu/glsl_real_types.inc"
#include "shaders/fields/candle.glsl"
}  // namespace tallow::geometry::candle_f64
