// The surface patches of one cell, shared by the vertex and quad passes of dual contouring.
//
// Plain surface nets give a cell one vertex. A cell whose face has four sign changes (an
// ambiguous face) or whose inside corners touch only diagonally holds several separate sheets of
// surface; one vertex for all of them makes the edges across that face shared by four triangles.
// So, as in manifold dual contouring (Schaefer, Ju and Warren 2007) and dual marching cubes
// (Nielson 2004), a cell gets one vertex per patch: the sign-changing edges of the cell are
// joined by the surface's segments on the six faces, and each connected group of edges is a patch.
// An ambiguous face is decided by the asymptotic decider of Nielson and Hamann (1991): the
// inside corners are joined through the face when the bilinear interpolant is negative at its
// saddle, i.e. when a1·a2 > b1·b2 for the inside pair a and the outside pair b. Both cells that share
// a face see the same four values, decide the same, and so agree on the segments.
//
// One case remains: when the two segments of an ambiguous face belong to the same patch in both
// cells (a neck thinner than a cell passing through the face, or a ring of material around the
// face's centre), both segments would become the same mesh edge between the two cells' vertices,
// used by four triangles. There, each segment gets a face vertex of its own (the mean of its two
// crossings), owned by the cell below the face, and the quads on either side route through it, so
// the neck keeps a cross-section of four vertices. Then every mesh edge lies in exactly two
// triangles and the triangles around each vertex form a single disc.
#include "dual_contouring/vertex_record.glsl"

// Corner i of a cell sits at offset (i & 1, (i >> 1) & 1, (i >> 2) & 1).
const ivec2 kEdges[12] = ivec2[12](ivec2(0, 1), ivec2(2, 3), ivec2(4, 5), ivec2(6, 7),   // along x
                                   ivec2(0, 2), ivec2(1, 3), ivec2(4, 6), ivec2(5, 7),   // along y
                                   ivec2(0, 4), ivec2(1, 5), ivec2(2, 6), ivec2(3, 7));  // along z
// Each face's corners in cyclic order, and the edge from corner k to corner k + 1 (mod 4).
const ivec4 kFaceCorners[6] = ivec4[6](ivec4(0, 2, 6, 4), ivec4(1, 3, 7, 5), ivec4(0, 1, 5, 4),
                                       ivec4(2, 3, 7, 6), ivec4(0, 1, 3, 2), ivec4(4, 5, 7, 6));
const ivec4 kFaceEdges[6] = ivec4[6](ivec4(4, 10, 6, 8), ivec4(5, 11, 7, 9), ivec4(0, 9, 2, 8),
                                     ivec4(1, 11, 3, 10), ivec4(0, 5, 1, 4), ivec4(2, 7, 3, 6));
const int kNoPatch = 3;  // 2-bit label of an edge without a sign change (never looked up)

vec3 cellCorner(int i) { return vec3(i & 1, (i >> 1) & 1, (i >> 2) & 1); }

// An ambiguous face with corner values f0..f3 in cyclic order (f0, f2 of one sign, f1, f3 of the
// other): true when corners 0 and 2 are cut off by the surface's two segments, false when 1 and 3
// are. Symmetric in the order of the cycle; `precise` keeps both products rounded alike (no fused
// multiply-add), so every cell and pass that looks at the face decides identically.
bool cutsEvenCorners(float f0, float f1, float f2, float f3) {
  precise float even = f0 * f2;
  precise float odd = f1 * f3;
  bool evenInside = isInside(f0);
  bool joinInside = evenInside ? even > odd : odd > even;  // the saddle of the bilinear interpolant is inside
  return evenInside != joinInside;
}

// True when face f of a cell with corner values v has four sign changes.
bool faceIsAmbiguous(float v[8], int f) {
  ivec4 c = kFaceCorners[f];
  bool i0 = isInside(v[c.x]), i1 = isInside(v[c.y]), i2 = isInside(v[c.z]), i3 = isInside(v[c.w]);
  return i0 == i2 && i1 == i3 && i0 != i1;
}

bool hasAmbiguousFace(float v[8]) {
  for (int f = 0; f < 6; ++f)
    if (faceIsAmbiguous(v, f)) return true;
  return false;
}

int gParent[12];
int patchRoot(int e) {
  while (gParent[e] != e) e = gParent[e];
  return e;
}
void joinEdges(int a, int b) { gParent[patchRoot(a)] = patchRoot(b); }

// 2 bits per edge (bits 2e, 2e + 1): the patch of each sign-changing edge, patches numbered
// 0, 1, … in order of their lowest edge. `count` receives the number of patches (0 to 4).
uint cellPatches(float v[8], out int count) {
  for (int e = 0; e < 12; ++e) gParent[e] = e;
  for (int f = 0; f < 6; ++f) {
    ivec4 c = kFaceCorners[f], e = kFaceEdges[f];
    bvec4 inside = bvec4(isInside(v[c.x]), isInside(v[c.y]), isInside(v[c.z]), isInside(v[c.w]));
    bvec4 crosses = notEqual(inside, inside.yzwx);  // edge k runs from corner k to corner k + 1
    int n = int(crosses.x) + int(crosses.y) + int(crosses.z) + int(crosses.w);
    if (n == 2) {
      int first = -1;
      for (int k = 0; k < 4; ++k)
        if (crosses[k]) {
          if (first < 0) first = e[k]; else joinEdges(first, e[k]);
        }
    } else if (n == 4) {
      // The corners that are not joined are cut off: each one's two edges form a segment.
      if (cutsEvenCorners(v[c.x], v[c.y], v[c.z], v[c.w])) { joinEdges(e.w, e.x); joinEdges(e.y, e.z); }
      else { joinEdges(e.x, e.y); joinEdges(e.z, e.w); }
    }
  }
  int label[12];
  for (int e = 0; e < 12; ++e) label[e] = -1;
  uint bits = 0u;
  count = 0;
  for (int e = 0; e < 12; ++e) {
    int pid = kNoPatch;
    if (isInside(v[kEdges[e].x]) != isInside(v[kEdges[e].y])) {
      int r = patchRoot(e);
      if (label[r] < 0) label[r] = count++;
      pid = label[r];
    }
    bits |= uint(pid) << (2 * e);
  }
  return bits;
}

// The ambiguous face between cell `lower` and the cell above it along axis k, seen from the
// lattice: corners s00 = lower + k̂, s10 = s00 + û, s11 = s00 + û + ŵ, s01 = s00 + ŵ, with
// u = (k + 1) mod 3, w = (k + 2) mod 3. Returns the u offset (0 or 1) of the cut corner at sample
// `corner`, the slot of its segment's face vertex, or −1 when `corner` is not cut.
int faceVertexSlot(ivec3 lower, int k, ivec3 corner) {
  ivec3 kk = ivec3(0), u = ivec3(0), w = ivec3(0);
  kk[k] = 1;
  u[(k + 1) % 3] = 1;
  w[(k + 2) % 3] = 1;
  ivec3 s00 = lower + kk;
  bool even = cutsEvenCorners(fieldAt(s00), fieldAt(s00 + u), fieldAt(s00 + u + w), fieldAt(s00 + w));
  ivec3 d = corner - s00;
  int du = d[(k + 1) % 3], dw = d[(k + 2) % 3];
  return (du == dw) == even ? du : -1;
}
