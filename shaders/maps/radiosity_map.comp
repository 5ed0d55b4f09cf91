#version 450 core
// Step 2 as a compute pass: one invocation per texel of the K maps, reading the maps' own G-buffer
// (world position with the translucent slot, normal; map_gbuffer.frag after the depth pre-pass) and
// adding the gather (gather.glsl) to the map in place. Same inputs and seeds as the fragment pass,
// so the same result; on GPUs whose rasteriser-side shader units are few (NVIDIA H100: 4 of 132
// SMs run vertex, geometry and pixel work) it uses the whole chip.
#include "maps/gather.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

uniform sampler2DArray uMapPosition;  // xyz: x_o [m], w: the surface's slot + 1 (0: no surface)
uniform sampler2DArray uMapNormal;
layout(rgba32f, binding = 0) uniform image2DArray uMaps;

void main() {
  ivec3 id = ivec3(gl_GlobalInvocationID);
  ivec3 size = imageSize(uMaps);
  if (any(greaterThanEqual(id, size))) return;
  vec4 p = texelFetch(uMapPosition, id, 0);
  int slot = int(p.w + 0.5) - 1;
  if (slot < 0) return;
  vec3 n = texelFetch(uMapNormal, id, 0).xyz;
  vec3 b = gatherScatteredRadiosity(p.xyz, normalize(n), uvec2(id.xy), id.z, slot);
  imageStore(uMaps, id, imageLoad(uMaps, id) + vec4(b, 1.0));
}
