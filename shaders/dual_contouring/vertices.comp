#version 450 core
// Pass 2, compute stage (field.extraction=compute): one work group per active block (dispatched
// indirectly from the classify pass's count), one invocation per cell. A cell's vertices
// (cell_vertices.glsl) go to consecutive places reserved with one atomic, and the cell's first
// vertex straight into the index map, so the compute path needs no pass 3. Vertices past the
// buffer's capacity are dropped, and with them the index of a cell not stored whole, as the
// transform-feedback path drops them (the counter still counts them: the overflow check).
layout(local_size_x = BLOCK_CELLS * BLOCK_CELLS * BLOCK_CELLS) in;

#include "dual_contouring/cell_vertices.glsl"

layout(std430, binding = 2) writeonly buffer Vertices { DcVertex vertices[]; };
layout(r32i, binding = 0) uniform writeonly iimage3D uIndexMap;
uniform uint uCapacity;  // vertices the buffer holds

void main() {
  DcVertex made[kDcMaxCellVertices];
  int total = dcCellVertices(activeCell(int(gl_LocalInvocationIndex), int(gl_WorkGroupID.x)), made);
  if (total == 0) return;
  uint first = atomicAdd(vertexCount, uint(total));
  for (int i = 0; i < total; ++i)
    if (first + uint(i) < uCapacity) vertices[first + uint(i)] = made[i];
  if (first + uint(total) <= uCapacity) {
    int cell = made[0].cell, cells = uSamples - 1;
    imageStore(uIndexMap, ivec3(cell % cells, (cell / cells) % cells, cell / (cells * cells)), ivec4(int(first)));
  }
}
