#version 450 core
// Pass 4, compute stage (field.extraction=compute): one work group per active block, one
// invocation per cell. A cell's triangles (cell_quads.glsl) are appended to the mesh buffer in the
// transform-feedback path's layout (position, normal, vertex index per corner) at places reserved
// with one atomic, and the count of corners drawn grows by the corners stored. A cell whose
// triangles do not all fit is dropped whole; since places are reserved in increasing order, the
// stored triangles form a prefix of the buffer, as transform feedback leaves them.
layout(local_size_x = BLOCK_CELLS * BLOCK_CELLS * BLOCK_CELLS) in;

#include "dual_contouring/cell_quads.glsl"

struct DcCorner { float px, py, pz, nx, ny, nz; int vertex; };
layout(std430, binding = 4) writeonly buffer Mesh { DcCorner corners[]; };
// The corners stored (GpuDualContouring copies it into each draw command after the pass), three
// words unused, then every triangle made, stored or not (the overflow check).
layout(std430, binding = 5) buffer MeshCounts { uint cornerCount; uint unused[3]; uint trianglesMade; };
uniform uint uTriangleCapacity;  // triangles the mesh buffer holds

DcCorner cornerOf(int i) {
  DcVertex v = vertices[i];
  return DcCorner(v.px, v.py, v.pz, v.nx, v.ny, v.nz, i);
}

void main() {
  ivec3 made[kDcMaxCellTriangles];
  int n = dcCellTriangles(activeCell(int(gl_LocalInvocationIndex), int(gl_WorkGroupID.x)), made);
  if (n == 0) return;
  uint first = atomicAdd(trianglesMade, uint(n));
  if (first + uint(n) > uTriangleCapacity) return;
  for (int t = 0; t < n; ++t) {
    uint base = 3u * (first + uint(t));
    corners[base] = cornerOf(made[t].x);
    corners[base + 1u] = cornerOf(made[t].y);
    corners[base + 2u] = cornerOf(made[t].z);
  }
  atomicAdd(cornerCount, 3u * uint(n));
}
