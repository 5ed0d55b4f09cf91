#version 450 core
// Passes 2 and 4: one point per cell of an active block (gl_VertexID: cell in block,
// gl_InstanceID: active block), drawn with glDrawArraysIndirect.
#include "dual_contouring/lattice.glsl"

flat out ivec3 vCell;

void main() {
  vCell = activeCell(gl_VertexID, gl_InstanceID);
  gl_Position = vec4(0.0);
}
