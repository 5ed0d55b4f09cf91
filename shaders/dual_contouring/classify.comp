#version 450 core
// Pass 1: a block of BLOCK_CELLS³ cells is active when its samples straddle 0. Active blocks are
// appended to the list, and the indirect draw's instance count is the append counter, so the later
// passes draw BLOCK_CELLS³ points × active blocks (cost follows the surface, not the volume).
layout(local_size_x = 64) in;

uniform sampler3D uField;
uniform int uSamples;
uniform int uBlocks;

layout(std430, binding = 0) writeonly buffer ActiveBlocks { uint activeBlocks[]; };
// DrawArraysIndirectCommand {count, instanceCount, first, baseInstance}
layout(std430, binding = 1) buffer DrawCommand { uint count; uint instanceCount; uint first; uint baseInstance; };

void main() {
  uint b = gl_GlobalInvocationID.x;
  if (b >= uint(uBlocks * uBlocks * uBlocks)) return;
  ivec3 bc = ivec3(int(b) % uBlocks, (int(b) / uBlocks) % uBlocks, int(b) / (uBlocks * uBlocks));
  ivec3 lo = bc * BLOCK_CELLS;
  ivec3 hi = min(lo + BLOCK_CELLS, ivec3(uSamples - 1));  // inclusive: the block's cells' corners
  bool anyInside = false, anyOutside = false;
  for (int z = lo.z; z <= hi.z; ++z)
    for (int y = lo.y; y <= hi.y; ++y)
      for (int x = lo.x; x <= hi.x; ++x) {
        bool inside = texelFetch(uField, ivec3(x, y, z), 0).r < 0.0;
        anyInside = anyInside || inside;
        anyOutside = anyOutside || !inside;
      }
  if (anyInside && anyOutside) activeBlocks[atomicAdd(instanceCount, 1u)] = b;
}
