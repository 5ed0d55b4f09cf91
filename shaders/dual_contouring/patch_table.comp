#version 450 core
// The patches of all 256 sign configurations of a cell, built once per extractor by the same
// cellPatches() the vertex pass runs (so the table cannot disagree with it). Entry i: corner k
// inside when bit k of i is set. A configuration with an ambiguous face depends on the values, not
// only the signs, and is marked (bit 31) so that the vertex pass computes it per cell instead.
layout(local_size_x = 64) in;

#include "dual_contouring/lattice.glsl"
#include "dual_contouring/patches.glsl"

layout(std430, binding = 3) writeonly buffer PatchTable { uint patchTable[256]; };

void main() {
  int config = int(gl_GlobalInvocationID.x);
  if (config >= 256) return;
  float v[8];
  for (int k = 0; k < 8; ++k) v[k] = ((config >> k) & 1) != 0 ? -1.0 : 1.0;
  int count;
  uint bits = cellPatches(v, count);
  patchTable[config] = withPatch(bits, 0, max(count, 1)) | (hasAmbiguousFace(v) ? 0x80000000u : 0u);
}
