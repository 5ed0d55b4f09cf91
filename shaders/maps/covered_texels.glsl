// The map texels the history passes visit (issue 39, point 5): those with a surface in this frame's
// G-buffer or the last one's (a texel that lost its surface is reset too), listed by
// maps/covered_texels.comp and dispatched indirectly, instead of every texel of the K maps (about a
// quarter of them have a surface). uCompacted = 0 dispatches over every texel, as before.
layout(std430, binding = 10) buffer CoveredTexels {
  uint coveredCount;
  uint coveredGroups[3];  // glDispatchComputeIndirect's x, y, z
  uint coveredTexels[];   // (layer · size + y) · size + x
};
uniform int uCompacted;

// This invocation's texel of maps of `size` (local size 8 × 8), or ivec3(-1) for none.
ivec3 historyTexel(ivec3 size) {
  if (uCompacted == 0) return ivec3(gl_GlobalInvocationID);
  uint i = gl_WorkGroupID.x * 64u + gl_LocalInvocationIndex;
  if (i >= coveredCount) return ivec3(-1);
  uint t = coveredTexels[i], side = uint(size.x);
  return ivec3(int(t % side), int((t / side) % side), int(t / (side * side)));
}
