// Shared by the dual-contouring passes: the sampled lattice (GL_R32F 3D texture, value < 0 inside)
// and the block decomposition. BLOCK_CELLS is prepended by GpuDualContouring.
uniform sampler3D uField;   // n³ samples, texel (x, y, z) = sample (x, y, z)
uniform int uSamples;       // n
uniform int uBlocks;        // blocks per axis = ceil((n − 1) / BLOCK_CELLS)
uniform vec3 uOrigin;       // world position of sample (0, 0, 0)
uniform float uCellSize;    // world units between samples

layout(std430, binding = 0) readonly buffer ActiveBlocks { uint activeBlocks[]; };

float fieldAt(ivec3 s) { return texelFetch(uField, s, 0).r; }
bool isInside(float v) { return v < 0.0; }

ivec3 blockCoord(uint b) {
  int i = int(b);
  return ivec3(i % uBlocks, (i / uBlocks) % uBlocks, i / (uBlocks * uBlocks));
}

// Cell of the `local`-th cell (x fastest) in the `instance`-th active block; x < 0 when outside.
ivec3 activeCell(int local, int instance) {
  ivec3 l = ivec3(local % BLOCK_CELLS, (local / BLOCK_CELLS) % BLOCK_CELLS, local / (BLOCK_CELLS * BLOCK_CELLS));
  ivec3 c = blockCoord(activeBlocks[instance]) * BLOCK_CELLS + l;
  return any(greaterThanEqual(c, ivec3(uSamples - 1))) ? ivec3(-1) : c;
}

int cellIndex(ivec3 c) { return c.x + (uSamples - 1) * (c.y + (uSamples - 1) * c.z); }
