#version 450 core
// Pass 4, geometry-shader stage (the paper's): one invocation per cell of an active block emits the
// cell's triangles (cell_quads.glsl), captured by transform feedback as a triangle list of
// (position, normal, vertex index).
#include "dual_contouring/cell_quads.glsl"

layout(points) in;
layout(triangle_strip, max_vertices = 54) out;  // 3 × kDcMaxCellTriangles

flat in ivec3 vCell[];
out vec3 tfPosition;
out vec3 tfNormal;
flat out int tfVertex;

void emit(int i) {
  DcVertex v = vertices[i];
  tfPosition = vec3(v.px, v.py, v.pz);
  tfNormal = vec3(v.nx, v.ny, v.nz);
  tfVertex = i;
  EmitVertex();
}

void main() {
  ivec3 made[kDcMaxCellTriangles];
  int n = dcCellTriangles(vCell[0], made);
  for (int t = 0; t < n; ++t) {
    emit(made[t].x);
    emit(made[t].y);
    emit(made[t].z);
    EndPrimitive();
  }
}
