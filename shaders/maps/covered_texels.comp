#version 450 core
// Lists the map texels with a surface now or in the last frame (maps/covered_texels.glsl) and
// counts the work groups of 64 that will visit them.
#include "maps/covered_texels.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

uniform sampler2DArray uOldPosition;  // w: slot + 1 (0: no surface)
uniform sampler2DArray uNewPosition;

void main() {
  ivec3 id = ivec3(gl_GlobalInvocationID);
  ivec3 size = textureSize(uNewPosition, 0);
  if (any(greaterThanEqual(id, size))) return;
  if (texelFetch(uOldPosition, id, 0).w <= 0.0 && texelFetch(uNewPosition, id, 0).w <= 0.0) return;
  uint i = atomicAdd(coveredCount, 1u);
  if (i % 64u == 0u) atomicAdd(coveredGroups[0], 1u);
  coveredTexels[i] = (uint(id.z) * uint(size.y) + uint(id.y)) * uint(size.x) + uint(id.x);
}
