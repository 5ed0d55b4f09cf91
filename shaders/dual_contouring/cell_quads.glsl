// Pass 4's work for one cell, shared by the geometry-shader stage (quads.geom, captured by
// transform feedback) and the compute stage (quads.comp, appended to the mesh buffer): for each of
// the 3 edges leaving the cell's min corner that changes sign, a quad joining the vertices of the
// edge's patch in the 4 cells around it, counter-clockwise seen from outside (value > 0), as two
// triangles split along the shorter diagonal. Where two of the cells share a face with face
// vertices (patches.glsl), the quad's side between them runs through the face vertex of the edge's
// segment, and the polygon (up to 8 vertices) is triangulated as a fan.
#include "dual_contouring/lattice.glsl"
#include "dual_contouring/patches.glsl"

const int kDcMaxCellTriangles = 18;  // 3 edges × 6 triangles

layout(std430, binding = 2) readonly buffer Vertices { DcVertex vertices[]; };
layout(std430, binding = 1) readonly buffer VertexCounter { uint vertexCount; };
layout(r32i, binding = 0) uniform readonly iimage3D uIndexMap;
uniform uint uCapacity;  // vertices the buffer holds

vec3 positionOf(int i) { return vec3(vertices[i].px, vertices[i].py, vertices[i].pz); }
vec3 normalOf(int i) { return vec3(vertices[i].nx, vertices[i].ny, vertices[i].nz); }

// True when triangle a, b, c (in emission order) faces against its vertices' normals: a fold.
bool folds(int a, int b, int c) {
  vec3 pa = positionOf(a);
  return dot(cross(positionOf(b) - pa, positionOf(c) - pa), normalOf(a) + normalOf(b) + normalOf(c)) <= 0.0;
}

// First vertex of `cell` in this extraction and its bits, or −1. The index map is never cleared
// (a clear would cost time in proportion to the volume), so an entry is trusted only when the
// vertex it names is this cell's first vertex and all of the cell's vertices were stored; a stale
// entry from an earlier extraction, or one of a cell whose vertices were dropped (overflow), fails.
int cellFirstVertex(ivec3 cell, out uint bits) {
  int first = imageLoad(uIndexMap, cell).r;
  uint stored = min(vertexCount, uCapacity);
  bits = 0u;
  if (first < 0 || uint(first) >= stored) return -1;
  bits = vertices[first].bits;
  bool valid = vertices[first].cell == cellIndex(cell) && !isFaceVertex(bits) && ownPatch(bits) == 0 &&
               uint(first + vertexTotal(bits)) <= stored;
  return valid ? first : -1;
}

// The face vertex on the side between `lower` (first vertex `first`, bits `bits`) and the cell
// above it along k, for the lattice edge from sample `start` to `start + a` in that face; −1 when
// the face has none (the common case, decided from the bits already loaded).
int faceVertex(int first, uint bits, ivec3 lower, int k, ivec3 start, ivec3 a) {
  if ((faceFlags(bits) & (1u << k)) == 0u) return -1;
  int slot = faceVertexSlot(lower, k, start);  // the edge's cut end names its segment
  if (slot < 0) slot = faceVertexSlot(lower, k, start + a);
  return first + faceVertexOffset(bits, k, slot);
}

// The triangles of cell c (its min corner's three edges), as vertex-buffer indices in outward
// winding. Returns how many (0 … kDcMaxCellTriangles).
int dcCellTriangles(ivec3 c, out ivec3 made[kDcMaxCellTriangles]) {
  int n = 0;
  if (c.x < 0) return 0;
  bool inside0 = isInside(fieldAt(c));
  for (int axis = 0; axis < 3; ++axis) {
    // (a, u, w) right-handed, so q0..q3 below run counter-clockwise seen from +a.
    ivec3 a = ivec3(0), u = ivec3(0), w = ivec3(0);
    a[axis] = 1;
    u[(axis + 1) % 3] = 1;
    w[(axis + 2) % 3] = 1;
    if (c[(axis + 1) % 3] == 0 || c[(axis + 2) % 3] == 0) continue;  // open at the lattice boundary
    if (isInside(fieldAt(c + a)) == inside0) continue;
    // Local edge numbers (patches.glsl) are 4·axis + x + 2y, 4·axis + x + 2z or 4·axis + y + 2z for
    // edges along z, y or x: an offset along u weighs 1 and along w 2, except for axis y, where
    // u = z weighs 2 and w = x weighs 1. The cell c − u − w sees the edge at offset (1, 1), and so on.
    int du = axis == 1 ? 2 : 1, dw = axis == 1 ? 1 : 2;
    uint b0, b1, b2, b3;
    int f0 = cellFirstVertex(c - u - w, b0), f1 = cellFirstVertex(c - w, b1);
    int f2 = cellFirstVertex(c, b2), f3 = cellFirstVertex(c - u, b3);
    if (min(min(f0, f1), min(f2, f3)) < 0) continue;  // a vertex was dropped (overflow)
    int q0 = f0 + edgePatch(b0, 4 * axis + du + dw), q1 = f1 + edgePatch(b1, 4 * axis + dw);
    int q2 = f2 + edgePatch(b2, 4 * axis), q3 = f3 + edgePatch(b3, 4 * axis + du);
    // The polygon q0, (f01), q1, (f12), q2, (f23), q3, (f30); sides q0–q1 and q2–q3 cross faces
    // normal to u, sides q1–q2 and q3–q0 faces normal to w (lower cells q0, q1, q3, q0).
    int ku = (axis + 1) % 3, kw = (axis + 2) % 3;
    int f01 = faceVertex(f0, b0, c - u - w, ku, c, a), f12 = faceVertex(f1, b1, c - w, kw, c, a);
    int f23 = faceVertex(f3, b3, c - u, ku, c, a), f30 = faceVertex(f0, b0, c - u - w, kw, c, a);
    int poly[8];
    int m = 0;
    poly[m++] = q0;
    if (f01 >= 0) poly[m++] = f01;
    poly[m++] = q1;
    if (f12 >= 0) poly[m++] = f12;
    poly[m++] = q2;
    if (f23 >= 0) poly[m++] = f23;
    poly[m++] = q3;
    if (f30 >= 0) poly[m++] = f30;
    if (!inside0) {  // outside at the edge's start: the outward normal is −a, reverse the polygon
      for (int i = 1, j = m - 1; i < j; ++i, --j) {
        int t = poly[i];
        poly[i] = poly[j];
        poly[j] = t;
      }
    }
    if (m == 4) {
      // Split along the shorter diagonal: fewer slivers on bent quads; unless that folds a triangle
      // over and the other diagonal does not (a quad across a sharp edge whose QEF vertices lie on
      // the edge can be split across it).
      bool split02 = distance(positionOf(poly[0]), positionOf(poly[2])) <= distance(positionOf(poly[1]), positionOf(poly[3]));
      bool folds02 = folds(poly[0], poly[1], poly[2]) || folds(poly[0], poly[2], poly[3]);
      bool folds13 = folds(poly[0], poly[1], poly[3]) || folds(poly[1], poly[2], poly[3]);
      if (split02 ? folds02 && !folds13 : folds13 && !folds02) split02 = !split02;
      if (split02) {
        made[n++] = ivec3(poly[0], poly[1], poly[2]);
        made[n++] = ivec3(poly[0], poly[2], poly[3]);
      } else {
        made[n++] = ivec3(poly[0], poly[1], poly[3]);
        made[n++] = ivec3(poly[1], poly[2], poly[3]);
      }
    } else {
      // A fan from a face vertex: a fan from a cell vertex would add the diagonal between the two
      // cells that the face vertex keeps apart, the very edge that would be used four times.
      int r = 0;
      while (!isFaceVertex(vertices[poly[r]].bits)) ++r;
      for (int i = 1; i + 1 < m; ++i) made[n++] = ivec3(poly[r], poly[(r + i) % m], poly[(r + i + 1) % m]);
    }
  }
  return n;
}
