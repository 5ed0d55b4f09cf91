// Pass 2's work for one cell, shared by the geometry-shader stage (vertices.geom, captured by
// transform feedback) and the compute stage (vertices.comp, written to the buffer directly): the
// vertices of the cell's surface patches and face vertices, in the order the later passes expect
// (vertex_record.glsl). One vertex per patch (see patches.glsl) at the mean of the patch's edge
// crossings (surface nets, Gibson 1998), or, built with DC_QEF, at the minimum of the probabilistic
// quadric of their tangent planes kept inside the cell (qef.glsl; the normal at a crossing is the
// lattice's gradient there, crossingGradient below); then the face vertices the cell owns; normal =
// normalised field gradient by central differences on the texture, or, built with DC_BLOB_NORMALS /
// DC_CANDLE_NORMALS (the fields filled on the GPU by fields/lattice.comp), the field's analytic
// gradient at the vertex (fields/blob.glsl, fields/candle.glsl: the lines
// geometry::BlobField::gradient and CandleField::gradient evaluate), the lattice's where that is 0
// (a point on the wick's axis).
#include "dual_contouring/lattice.glsl"
#include "dual_contouring/patches.glsl"
// Outside the #ifdefs: the loader expands each file once per stage, where it is first included,
// whatever the preprocessor later keeps, so a file both variants need must not first appear in one.
#include "common/shared.glsl"
#include "bssrdf/real.glsl"
#ifdef DC_QEF
#include "dual_contouring/qef.glsl"
#endif
#if defined(DC_BLOB_NORMALS)
#include "fields/blob_uniforms.glsl"
vec3 analyticGradientAt(vec3 p) { return blobGradientAt(p); }
#define DC_ANALYTIC_NORMALS
#elif defined(DC_CANDLE_NORMALS)
#include "fields/candle_uniforms.glsl"
vec3 analyticGradientAt(vec3 p) { return candleGradientAt(p); }
#define DC_ANALYTIC_NORMALS
#endif

const int kDcMaxCellVertices = 10;  // 4 patches + 3 faces × 2

// {count, groupsX, groupsY, groupsZ}: vertices made so far; the geometry-shader stage also builds
// the indirect dispatch of the index-map pass from it (one work group per 64 vertices).
layout(std430, binding = 1) buffer VertexCounter { uint vertexCount; uint groupsX; uint groupsY; uint groupsZ; };
// Patches of each sign configuration (patch_table.comp); bit 31: has an ambiguous face.
layout(std430, binding = 3) readonly buffer PatchTable { uint patchTable[256]; };

float sampleLinear(vec3 s) { return texture(uField, (s + 0.5) / float(uSamples)).r; }

// Crossing of the lattice edge a → b (samples of opposite sign), lattice coordinates.
vec3 crossing(ivec3 a, ivec3 b) {
  float va = fieldAt(a), vb = fieldAt(b);
  return mix(vec3(a), vec3(b), clamp(va / (va - vb), 0.0, 1.0));
}

#ifdef DC_QEF
float fieldClamped(ivec3 s) { return fieldAt(clamp(s, ivec3(0), ivec3(uSamples - 1))); }

// ∇ of the field at the crossing at fraction t of the lattice edge from sample a to a + ê_k, from
// the lattice alone (whatever filled it), in field units per lattice unit. Along the edge: the
// edge's own difference. Across it, along each other axis j: the values interpolated at the same t
// on the parallel lattice edges one and two samples away, differentiated by dcLatticeDerivative
// (qef.glsl: central, or one-sided away from a crease that the central stencil straddles).
vec3 crossingGradient(ivec3 a, int k, float t) {
  ivec3 ek = ivec3(0);
  ek[k] = 1;
  vec3 g;
  g[k] = fieldAt(a + ek) - fieldAt(a);
  for (int i = 1; i < 3; ++i) {
    int j = (k + i) % 3;
    ivec3 ej = ivec3(0);
    ej[j] = 1;
    float f[5];
    for (int m = -2; m <= 2; ++m) f[m + 2] = mix(fieldClamped(a + m * ej), fieldClamped(a + ek + m * ej), t);
    g[j] = dcLatticeDerivative(f[0], f[1], f[2], f[3], f[4]);
  }
  return g;
}
#endif

// The vertex at lattice position s of `cell`, with its normal and bits.
DcVertex dcVertexAt(vec3 s, int cell, uint bits) {
  vec3 position = uOrigin + uCellSize * s;
  const float h = 0.5;  // half-cell central differences (trilinear texture)
#ifdef DC_ANALYTIC_NORMALS
  vec3 g = analyticGradientAt(position);  // analytic: exact at the vertex, no lattice error
  if (dot(g, g) == 0.0)  // on a medial axis (the wick's): the lattice's slope
#else
  vec3 g;
#endif
  g = vec3(sampleLinear(s + vec3(h, 0, 0)) - sampleLinear(s - vec3(h, 0, 0)),
           sampleLinear(s + vec3(0, h, 0)) - sampleLinear(s - vec3(0, h, 0)),
           sampleLinear(s + vec3(0, 0, h)) - sampleLinear(s - vec3(0, 0, h)));
  float len = length(g);
  vec3 n = len > 0.0 ? g / len : vec3(0.0, 1.0, 0.0);
  return DcVertex(position.x, position.y, position.z, n.x, n.y, n.z, cell, bits);
}

// The vertices of cell c (none unless it changes sign), in order: its patches, then its face
// vertices. Returns how many (0 … kDcMaxCellVertices).
int dcCellVertices(ivec3 c, out DcVertex made[kDcMaxCellVertices]) {
  if (c.x < 0) return 0;
  float v[8];
  int config = 0;
  for (int i = 0; i < 8; ++i) {
    v[i] = fieldAt(c + ivec3(cellCorner(i)));
    config |= isInside(v[i]) ? 1 << i : 0;
  }
  if (config == 0 || config == 255) return 0;

  // Most cells: the table. A cell with an ambiguous face: its values decide (asymptotic decider).
  uint entry = patchTable[config];
  int count = patchCount(entry);
  uint bits = entry & 0x00FFFFFFu;
  bool ambiguous = (entry & 0x80000000u) != 0u;
  if (ambiguous) bits = cellPatches(v, count);
  vec3 sum[4] = vec3[4](vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0));
  float crossings[4] = float[4](0.0, 0.0, 0.0, 0.0);
#ifdef DC_QEF
  DcQuadric quadric[4] = DcQuadric[4](dcQuadricEmpty(), dcQuadricEmpty(), dcQuadricEmpty(), dcQuadricEmpty());
#endif
  for (int e = 0; e < 12; ++e) {
    int a = kEdges[e].x, b = kEdges[e].y;
    if (isInside(v[a]) == isInside(v[b])) continue;
    int p = edgePatch(bits, e);
    float t = clamp(v[a] / (v[a] - v[b]), 0.0, 1.0);
    vec3 x = mix(cellCorner(a), cellCorner(b), t);
    sum[p] += x;
    crossings[p] += 1.0;
#ifdef DC_QEF
    vec3 g = crossingGradient(c + ivec3(cellCorner(a)), e / 4, t);  // kEdges: 4 edges per axis, from the lower corner
    float len = length(g);
    quadric[p] = dcQuadricAdd(quadric[p], x, len > 0.0 ? g / len : vec3(0.0));
#endif
  }

  // Upper faces whose two segments join the same patch on both sides get face vertices.
  uint flags = 0u;
  for (int k = 0; k < 3; ++k) {
    if (!ambiguous || c[k] + 1 >= uSamples - 1 || !faceIsAmbiguous(v, 2 * k + 1)) continue;
    ivec4 e = kFaceEdges[2 * k + 1];  // this cell's upper face along k (opposite edges e.x, e.z lie in different segments)
    if (edgePatch(bits, e.x) != edgePatch(bits, e.z)) continue;
    ivec3 kk = ivec3(0);
    kk[k] = 1;
    float above[8];
    for (int i = 0; i < 8; ++i) above[i] = fieldAt(c + kk + ivec3(cellCorner(i)));
    int aboveCount;
    uint aboveBits = cellPatches(above, aboveCount);
    ivec4 eb = kFaceEdges[2 * k];  // the same face, the lower face of the cell above
    if (edgePatch(aboveBits, eb.x) == edgePatch(aboveBits, eb.z)) flags |= 1u << k;
  }
  bits = withPatch(bits, 0, count) | (flags << 28);

  uint cellBits = bits & ~(3u << 24);  // without the own-patch field
  int cell = cellIndex(c);
  int m = 0;
  for (int p = 0; p < count; ++p) {
#ifdef DC_QEF
    vec3 inCell = dcLimitToLattice(v, dcQuadricMassPoint(quadric[p]), dcQuadricVertex(quadric[p], DC_QEF_SIGMA_N));
#else
    vec3 inCell = sum[p] / crossings[p];
#endif
    made[m++] = dcVertexAt(vec3(c) + inCell, cell, cellBits | (uint(p) << 24));
  }
  for (int k = 0; k < 3; ++k) {
    if ((flags & (1u << k)) == 0u) continue;
    ivec3 kk = ivec3(0), u = ivec3(0), w = ivec3(0);
    kk[k] = 1;
    u[(k + 1) % 3] = 1;
    w[(k + 2) % 3] = 1;
    ivec3 s00 = c + kk;
    for (int slot = 0; slot < 2; ++slot) {
      // The cut corner with u offset `slot`, and its segment's two crossings.
      ivec3 cut = faceVertexSlot(c, k, s00 + slot * u) == slot ? s00 + slot * u : s00 + slot * u + w;
      ivec3 du = slot == 0 ? u : -u;
      ivec3 dw = cut == s00 + slot * u ? w : -w;
      made[m++] = dcVertexAt(0.5 * (crossing(cut, cut + du) + crossing(cut, cut + dw)), cell, cellBits | 0x80000000u);
    }
  }
  return m;  // = vertexTotal(bits)
}
