// Dual contouring's vertex placement by a quadric error function (field.placement=qef), written in
// the GLSL/C++ subset (common/shared.glsl) so that the vertex pass (vertices.geom, built with
// DC_QEF) and the C++ tests (tests/qef_test.cpp) run the same lines. Coordinates are the cell's
// own: its corners at 0 and 1 on each axis, lattice units.
//
// Each edge crossing p_i of a patch, with the unit normal n_i of the field there, is a tangent
// plane. Dual contouring (Ju et al. 2002) puts the vertex at the minimum of Σ (n_iᵀ(x − p_i))²,
// which is singular on flat and cylindrical patches (no unique minimum) and unstable where the
// normals nearly agree. Probabilistic quadrics (Trettner and Kobbelt, "Fast and Robust QEF
// Minimization using Probabilistic Quadrics", Eurographics 2020) take each plane as uncertain —
// its normal n ~ N(n_i, σ_n² I), its point p ~ N(p_i, σ_p² I), independent — and minimise the
// expected squared distance. Expanding n = n_i + ε_n, p = p_i + ε_p, the cross terms vanish in
// expectation and
//   E[(nᵀ(x − p))²] = (x − p_i)ᵀ (n_i n_iᵀ + σ_n² I) (x − p_i) + σ_p² (n_iᵀ n_i + 3 σ_n²),
// the paper's isotropic plane quadric: A_i = n_i n_iᵀ + σ_n² I, b_i = A_i p_i. The σ_p term is a
// constant that does not move the minimum, so it is left out. Summed over the k crossings, the
// gradient vanishes where
//   (Σ n_i n_iᵀ + k σ_n² I) x = Σ n_i n_iᵀ p_i + σ_n² Σ p_i,
// a symmetric positive definite 3×3 system (every eigenvalue ≥ k σ_n²), solved in closed form.
// Written about the mass point m = Σ p_i / k it reads
//   x = m + (Σ n_i n_iᵀ + k σ_n² I)⁻¹ Σ n_i n_iᵀ (p_i − m),
// so the σ_n² term is a Tikhonov pull toward the mass point: on a flat patch (every n_i alike)
// x = m exactly; across a crease whose normals differ by an angle θ the planes win over the pull
// when θ²/4 ≫ σ_n² (the smaller eigenvalue of Σ n_i n_iᵀ over the two planes is about k θ²/4).
#ifdef TALLOW_GLSL
#include "common/shared.glsl"
#endif

// σ_n, the normals' standard deviation (radians, for unit normals): creases sharper than about
// 2σ_n ≈ 11° are followed, gentler bends and normals that scatter less than that stay near the
// mass point. Of 0.05, 0.1 and 0.2, tried on the rotated cube of `tallow probe placement` at 32³
// and 48³ (these lines replayed on the CPU), 0.1 put the vertices of the cells astride its edges
// nearest to the edges (median 0.10 and 0.15 cells, against 0.12 and 0.16 for 0.05 and 0.13 and
// 0.16 for 0.2); on the sphere the three were within 0.002 cells of each other.
const float DC_QEF_SIGMA_N = 0.1f;

// The normals. At a crossing the field's gradient is estimated from the lattice (vertices.geom,
// crossingGradient): across the edge, from values one and two samples away on either side. Central
// differences smear a crease over their two-sample stencil — within a cell of a sharp edge of a
// signed distance they blend the two faces' normals, about 20° off for a cube's edge — which pulls
// the QEF's vertex back toward the mass point. So, as ENO schemes do for level sets (Harten et al.
// 1987; Osher and Sethian 1988), the stencil is chosen by smoothness: the central difference where
// its second difference is no larger than DC_ENO_RATIO times the smaller one-sided one (smooth
// surfaces: second-order accurate), otherwise the one-sided difference on the side with the smaller
// second difference (the side that does not reach across the crease). Second differences under
// DC_ENO_FLAT of the first differences count as a straight line (a plane's field: central).
const float DC_ENO_RATIO = 2.0f;
const float DC_ENO_FLAT = 1e-3f;

// The derivative at f0 of samples f(−2), f(−1), f0, f(1), f(2) one lattice unit apart.
TALLOW_FN float dcLatticeDerivative(float fm2, float fm1, float f0, float fp1, float fp2) {
  float backward = f0 - fm1;
  float forward = fp1 - f0;
  float curveCentral = abs(fp1 - 2.0f * f0 + fm1);
  float curveBackward = abs(f0 - 2.0f * fm1 + fm2);
  float curveForward = abs(fp2 - 2.0f * fp1 + f0);
  float smoothLimit = DC_ENO_RATIO * min(curveBackward, curveForward) + DC_ENO_FLAT * (abs(backward) + abs(forward));
  if (curveCentral <= smoothLimit) return 0.5f * (backward + forward);
  return curveBackward <= curveForward ? backward : forward;
}

// The quadric of one patch, accumulated crossing by crossing.
struct DcQuadric {
  mat3 a;          // Σ n_i n_iᵀ
  vec3 b;          // Σ n_i (n_i · p_i)
  vec3 pointSum;   // Σ p_i
  float count;     // k
};

TALLOW_FN DcQuadric dcQuadricEmpty() {
  DcQuadric q;
  q.a = mat3(0.0f);
  q.b = vec3(0.0f);
  q.pointSum = vec3(0.0f);
  q.count = 0.0f;
  return q;
}

// Adds the tangent plane through crossing p with unit normal n (n = 0 where the field has no
// gradient: the crossing then only pulls toward itself through the σ_n² term).
TALLOW_FN DcQuadric dcQuadricAdd(DcQuadric q, vec3 p, vec3 n) {
  q.a += outerProduct(n, n);
  q.b += n * dot(n, p);
  q.pointSum += p;
  q.count += 1.0f;
  return q;
}

TALLOW_FN vec3 dcQuadricMassPoint(DcQuadric q) { return q.pointSum / q.count; }

// The minimum of the summed probabilistic quadrics (above) for normal deviation sigmaN > 0.
TALLOW_FN vec3 dcQuadricMinimum(DcQuadric q, float sigmaN) {
  vec3 m = dcQuadricMassPoint(q);
  mat3 regularised = q.a + mat3(q.count * sigmaN * sigmaN);
  return m + inverse(regularised) * (q.b - q.a * m);
}

// How far inside its cell's faces a vertex stays, in cells. On the faces themselves, two
// neighbouring cells' vertices could meet at one point (both clamped to the face they share, or a
// mass point on it where every crossing lies on that face) and their quad would have a triangle of
// zero area: the random candle t = 7.75756 at 83³ had eight (tests/dual_contouring_quality_gltest.cpp,
// TALLOW_TEST_SEED=2447795320). A thousandth of a cell moves no vertex measurably.
const float DC_CELL_MARGIN = 1e-3f;

// Keeps the vertex in its cell: x when it lies in [m, 1 − m]³ (m = DC_CELL_MARGIN), otherwise the
// point where the segment from the mass point (inside: a mean of points on the cell's edges) toward
// x leaves that box. The quadric is convex and decreases from the mass point to x, so that point is
// the lowest of the segment that the box holds, and every vertex stays in its own cell.
TALLOW_FN vec3 dcKeepInCell(vec3 m, vec3 x) {
  const float lo = DC_CELL_MARGIN, hi = 1.0f - DC_CELL_MARGIN;
  vec3 d = x - m;
  float t = 1.0f;
  for (int i = 0; i < 3; ++i) {
    if (d[i] > 0.0f) t = min(t, (hi - m[i]) / d[i]);
    if (d[i] < 0.0f) t = min(t, (m[i] - lo) / -d[i]);
  }
  return clamp(m + max(t, 0.0f) * d, vec3(lo), vec3(hi));
}

// The vertex of a patch: the quadric's minimum, kept in the cell.
TALLOW_FN vec3 dcQuadricVertex(DcQuadric q, float sigmaN) {
  return dcKeepInCell(dcQuadricMassPoint(q), dcQuadricMinimum(q, sigmaN));
}

// How far the tangent planes may take a vertex from the lattice's own surface, the zero set of the
// cell's trilinear interpolant (lattice units). The lattice cannot tell a sharp edge from one
// rounded within a cell, and its interpolant cuts a right-angled edge of a signed distance by up to
// about 0.45 cells, so a QEF vertex on such an edge stands that far from it; beyond that the planes
// are extrapolating, as at the tip of a thin rounded ridge (near the top of the bunny's level set on
// a 48³ lattice the planes met 0.58 cells outside its surface; limited, the farthest vertex is 0.30).
const float DC_QEF_MAX_LATTICE_DISTANCE = 0.5f;

// First-order distance |f| / |∇f| from x (cell coordinates) to the zero set of the trilinear
// interpolant of the cell's corner values v (corner i at (i & 1, (i >> 1) & 1, (i >> 2) & 1)).
TALLOW_FN float dcTrilinearDistance(float v[8], vec3 x) {
  float value = 0.0f;
  vec3 g = vec3(0.0f);
  for (int i = 0; i < 8; ++i) {
    vec3 corner = vec3(float(i & 1), float((i >> 1) & 1), float((i >> 2) & 1));
    vec3 w = mix(vec3(1.0f) - x, x, corner);         // the corner's weight per axis
    vec3 dw = mix(vec3(-1.0f), vec3(1.0f), corner);  // its derivative
    value += v[i] * w.x * w.y * w.z;
    g += v[i] * vec3(dw.x * w.y * w.z, w.x * dw.y * w.z, w.x * w.y * dw.z);
  }
  float len = length(g);
  return len > 0.0f ? abs(value) / len : 0.0f;
}

// x, or, when it lies farther than DC_QEF_MAX_LATTICE_DISTANCE from the lattice's surface, the
// farthest point of the segment from the mass point m toward x that does not (bisection to 1/256 of
// the segment; m itself when even it is that far).
TALLOW_FN vec3 dcLimitToLattice(float v[8], vec3 m, vec3 x) {
  if (dcTrilinearDistance(v, x) <= DC_QEF_MAX_LATTICE_DISTANCE) return x;
  float lo = 0.0f, hi = 1.0f;
  for (int i = 0; i < 8; ++i) {
    float mid = 0.5f * (lo + hi);
    if (dcTrilinearDistance(v, mix(m, x, mid)) <= DC_QEF_MAX_LATTICE_DISTANCE) lo = mid;
    else hi = mid;
  }
  return mix(m, x, lo);
}
