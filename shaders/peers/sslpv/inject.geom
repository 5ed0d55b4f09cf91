#version 450 core
// SSLPV injection: one texel's point into its cell, layer z of the grid (gl_Layer), pixel (x, y).
layout(points) in;
layout(points, max_vertices = 1) out;

uniform int uGridSize;

flat in ivec3 vCell[];
flat in vec4 vR[], vG[], vB[];
flat out vec4 fR, fG, fB;

void main() {
  ivec3 cell = vCell[0];
  if (cell.x < 0) return;
  gl_Layer = cell.z;
  gl_Position = vec4((vec2(cell.xy) + 0.5) / float(uGridSize) * 2.0 - 1.0, 0.0, 1.0);
  fR = vR[0];
  fG = vG[0];
  fB = vB[0];
  EmitVertex();
  EndPrimitive();
}
