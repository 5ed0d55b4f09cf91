#version 450 core
// Pass 4: for each of the 3 edges leaving the cell's min corner that changes sign, a quad joining
// the vertices of the 4 cells around it, as two triangles, counter-clockwise seen from outside
// (value > 0). Captured by transform feedback as a triangle list of (position, normal).
#include "dual_contouring/lattice.glsl"

layout(points) in;
layout(triangle_strip, max_vertices = 18) out;

flat in ivec3 vCell[];
out vec3 tfPosition;
out vec3 tfNormal;

struct DcVertex { float px, py, pz, nx, ny, nz; int cell; };
layout(std430, binding = 2) readonly buffer Vertices { DcVertex vertices[]; };
layout(r32i, binding = 0) uniform readonly iimage3D uIndexMap;

void emit(int i) {
  DcVertex v = vertices[i];
  tfPosition = vec3(v.px, v.py, v.pz);
  tfNormal = vec3(v.nx, v.ny, v.nz);
  EmitVertex();
}

void emitTriangle(int a, int b, int c) {
  emit(a);
  emit(b);
  emit(c);
  EndPrimitive();
}

void main() {
  ivec3 c = vCell[0];
  if (c.x < 0) return;
  bool inside0 = isInside(fieldAt(c));
  for (int axis = 0; axis < 3; ++axis) {
    // (a, u, w) right-handed, so q0..q3 below run counter-clockwise seen from +a.
    ivec3 a = ivec3(0), u = ivec3(0), w = ivec3(0);
    a[axis] = 1;
    u[(axis + 1) % 3] = 1;
    w[(axis + 2) % 3] = 1;
    if (c[(axis + 1) % 3] == 0 || c[(axis + 2) % 3] == 0) continue;  // open at the lattice boundary
    if (isInside(fieldAt(c + a)) == inside0) continue;
    int q0 = imageLoad(uIndexMap, c - u - w).r, q1 = imageLoad(uIndexMap, c - w).r;
    int q2 = imageLoad(uIndexMap, c).r, q3 = imageLoad(uIndexMap, c - u).r;
    if (min(min(q0, q1), min(q2, q3)) < 0) continue;  // a vertex was dropped (overflow)
    if (inside0) {  // inside at the edge's start: the outward normal is +a
      emitTriangle(q0, q1, q2);
      emitTriangle(q0, q2, q3);
    } else {
      emitTriangle(q0, q2, q1);
      emitTriangle(q0, q3, q2);
    }
  }
}
