#version 450 core
// Pass 2, geometry-shader stage (the paper's): one invocation per cell of an active block emits the
// cell's vertices (cell_vertices.glsl), captured by transform feedback as (position, normal, cell,
// bits); the vertices of a cell are consecutive (one invocation emits them in order), and the
// index-map pass finds each cell's first one in the buffer. The counter also builds that pass's
// indirect dispatch (one work group per 64 vertices).
#include "dual_contouring/cell_vertices.glsl"

layout(points) in;
layout(points, max_vertices = 10) out;  // kDcMaxCellVertices

flat in ivec3 vCell[];
out vec3 tfPosition;
out vec3 tfNormal;
flat out int tfCell;
flat out int tfBits;

void main() {
  DcVertex made[kDcMaxCellVertices];
  int total = dcCellVertices(vCell[0], made);
  if (total == 0) return;
  // A group of the index-map dispatch starts at every multiple of 64 in [first, first + total).
  uint first = atomicAdd(vertexCount, uint(total));
  atomicAdd(groupsX, (first + uint(total) + 63u) / 64u - (first + 63u) / 64u);
  for (int i = 0; i < total; ++i) {
    tfPosition = vec3(made[i].px, made[i].py, made[i].pz);
    tfNormal = vec3(made[i].nx, made[i].ny, made[i].nz);
    tfCell = made[i].cell;
    tfBits = int(made[i].bits);
    EmitVertex();
    EndPrimitive();
  }
}
