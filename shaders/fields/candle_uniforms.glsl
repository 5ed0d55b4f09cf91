// The candle at time t as uniforms (GLSL only): set by geometry::GpuCandleField from a CandleField
// (its CandleShape, computed once per frame by candleShapeAt in double), read by the lattice fill
// (fields/lattice.comp with FIELD_CANDLE) and the vertex normals (dual_contouring/vertices.geom with
// DC_CANDLE_NORMALS) through fields/candle.glsl.
#include "fields/candle.glsl"

uniform CandleShape uCandle;

float candleValueAt(vec3 p) { return candleFieldValue(p, uCandle); }
vec3 candleGradientAt(vec3 p) { return candleFieldGradient(p, uCandle); }
