#version 450 core
// Fills the dual-contouring lattice (GL_R32F 3D texture, GpuDualContouring) with a melting mesh's
// field at t, one invocation per sample: sample s sits at uOrigin + uCellSize · s, as in
// geometry::SampledLattice. The NanoVDB grids were uploaded once; per frame only uniforms change.
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

#include "fields/melt_uniforms.glsl"

layout(r32f, binding = 0) uniform writeonly image3D uLattice;
uniform int uSamples;     // n: samples per axis
uniform vec3 uOrigin;     // world position of sample (0, 0, 0)
uniform float uCellSize;  // world units between samples

void main() {
  ivec3 s = ivec3(gl_GlobalInvocationID);
  if (any(greaterThanEqual(s, ivec3(uSamples)))) return;
  imageStore(uLattice, s, vec4(meltValueAt(uOrigin + uCellSize * vec3(s)), 0.0, 0.0, 0.0));
}
