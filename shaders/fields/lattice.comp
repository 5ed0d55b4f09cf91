#version 450 core
// Fills the dual-contouring lattice (GL_R32F 3D texture, GpuDualContouring) with an analytic field
// at t, one invocation per sample: sample s sits at uOrigin + uCellSize · s, as in
// geometry::SampledLattice. No CPU lattice and no upload: only the field's uniforms change per
// frame. The field is chosen by a define: FIELD_BLOB (fields/blob_uniforms.glsl, GpuBlobField) or
// FIELD_CANDLE (fields/candle_uniforms.glsl, GpuCandleField).
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

// Outside the #ifdefs: the loader expands each file once per stage, where it is first included,
// whatever the preprocessor later keeps, so the files every field needs come first.
#include "common/shared.glsl"
#include "bssrdf/real.glsl"
#if defined(FIELD_BLOB)
#include "fields/blob_uniforms.glsl"
float fieldValueAt(vec3 p) { return blobValueAt(p); }
#elif defined(FIELD_CANDLE)
#include "fields/candle_uniforms.glsl"
float fieldValueAt(vec3 p) { return candleValueAt(p); }
#else
#error "fields/lattice.comp: define FIELD_BLOB or FIELD_CANDLE"
#endif

layout(r32f, binding = 0) uniform writeonly image3D uLattice;
uniform int uSamples;     // n: samples per axis
uniform vec3 uOrigin;     // world position of sample (0, 0, 0)
uniform float uCellSize;  // world units between samples

void main() {
  ivec3 s = ivec3(gl_GlobalInvocationID);
  if (any(greaterThanEqual(s, ivec3(uSamples)))) return;
  imageStore(uLattice, s, vec4(fieldValueAt(uOrigin + uCellSize * vec3(s)), 0.0, 0.0, 0.0));
}
