// A melting mesh field at one point, written once for GLSL and C++ (the conventions of
// shaders/bssrdf/real.glsl: `real`/`real3`, unsuffixed literals wrapped in real(), TALLOW_FN, no
// include guards). The GPU evaluates it per lattice sample (fields/mesh_melt_lattice.comp);
// geometry::MeshLevelSetField::melted(t) evaluates the same lines in double (geometry/mesh_melt.cpp),
// so `tallow field`, `tallow mesh --cpu`, the CPU reference integrator and the renderer agree.
//
// What OpenVDB is needed for is built once per mesh (geometry::MeltGrids): the mesh's narrow-band
// level set and copies of it rounded by OpenVDB's mean-curvature flow (LevelSetFilter), stored one
// after another as NanoVDB float grids in one buffer, read here through PNanoVDB's read accessor
// (PNanoVDB.h, included before this file: as GLSL by fields/melt_uniforms.glsl over a shader
// storage buffer, as C by mesh_melt.cpp over the same bytes in memory). What changes with t is
// closed-form, from a few scalars the CPU computes per t (geometry::meltStateAt, like the blob's
// centres), evaluated here per point:
//   1. slump about the bottom centre a, keeping the volume: the shape at t is the unmelted one
//      under M(x, y, z) = a + (Δx/√s, Δy·s, Δz/√s), s = 1 − slump·f; its field at p is the grid's at
//      M⁻¹(p) = a + (Δx·√s, Δy/s, Δz·√s), times s: M⁻¹ stretches lengths by at most 1/s, so the
//      product stays a 1-Lipschitz lower bound on the distance (a valid signed distance bound);
//   2. rounding: a convex blend of the two smoothing levels that bracket slump's f·iterations of
//      mean-curvature flow (blending two distance fields keeps the Lipschitz bound);
//   3. the puddle: a disc of radius R and thickness h on the base, its rim rounded by h/2 (the
//      exact distance to a disc swept by a ball), joined by a polynomial smooth union whose radius
//      k ≤ the band's half-width at s, so that the grid's clamp at ±band never adds surface.
#ifdef TALLOW_GLSL
#include "common/shared.glsl"
#include "bssrdf/real.glsl"
#endif

// The per-t state of a melt (geometry::MeltState, rounded to float on the GPU).
struct MeltShape {
  real3 anchor;       // bottom centre of the unmelted shape, world units
  real heightScale;   // s = 1 − slump·f
  real invVoxel;      // index units per world unit of the grids
  uint gridA;         // byte address of the smoothing level below f·iterations
  uint gridB;         // … and above it
  real blend;         // weight of gridB, in [0, 1]
  real puddleRadius;  // R, world units
  real puddleHeight;  // h, world units; 0: no puddle yet
  real joinRadius;    // k of the smooth union, world units
  real3 boxLo;        // index-space box beyond which every level is its background (1.5 voxels
  real3 boxHi;        // outside the levels' active voxels: no corner of a sample there is active)
  real background;    // the grids' value outside their band, world units
};

// Trilinear sample of the NanoVDB float grid at byte address `grid` of `buf` at index-space point
// `index` (voxel centres at integers, as OpenVDB's BoxSampler); outside the narrow band the grid's
// tiles give ±band. One read accessor per call: the eight corners share one leaf almost always.
TALLOW_FN real meltGridSample(pnanovdb_buf_t buf, uint grid, real3 index) {
  pnanovdb_grid_handle_t handle;
  handle.address.byte_offset = grid;
  pnanovdb_root_handle_t root = pnanovdb_tree_get_root(buf, pnanovdb_grid_get_tree(buf, handle));
  pnanovdb_readaccessor_t acc;
  pnanovdb_readaccessor_init(PNANOVDB_REF(acc), root);
  real3 lower = floor(index);
  real3 w = index - lower;
  int i0 = int(lower.x);
  int j0 = int(lower.y);
  int k0 = int(lower.z);
  real v[8];
  for (int c = 0; c < 8; ++c) {
    pnanovdb_coord_t ijk;
    ijk.x = i0 + (c & 1);
    ijk.y = j0 + ((c >> 1) & 1);
    ijk.z = k0 + ((c >> 2) & 1);
    pnanovdb_address_t at =
        pnanovdb_readaccessor_get_value_address(PNANOVDB_GRID_TYPE_FLOAT, buf, PNANOVDB_REF(acc), PNANOVDB_REF(ijk));
    v[c] = real(pnanovdb_read_float(buf, at));
  }
  // Along x, then y, then z.
  real x00 = mix(v[0], v[1], w.x);
  real x10 = mix(v[2], v[3], w.x);
  real x01 = mix(v[4], v[5], w.x);
  real x11 = mix(v[6], v[7], w.x);
  return mix(mix(x00, x10, w.y), mix(x01, x11, w.y), w.z);
}

// Exact signed distance to the puddle: the disc of radius R − h/2 at height a.y + h/2 swept by a
// ball of radius h/2 (a flat bottom on the base, a rounded rim).
TALLOW_FN real meltPuddleDistance(real3 p, MeltShape m) {
  real r = real(0.5) * m.puddleHeight;
  real3 d = p - m.anchor;
  real radial = max(sqrt(d.x * d.x + d.z * d.z) - max(m.puddleRadius - r, real(0)), real(0));
  real vertical = abs(d.y - r);
  return sqrt(radial * radial + vertical * vertical) - r;
}

// Polynomial smooth minimum (radius k > 0): min(a, b) − k/4·h², h = max(k − |a − b|, 0)/k; its
// gradient is a convex combination of the two, so it keeps their Lipschitz bound.
TALLOW_FN real meltSmoothUnion(real a, real b, real k) {
  real h = max(k - abs(a - b), real(0)) / k;
  return min(a, b) - real(0.25) * k * h * h;
}

// The melted field at world point p: negative inside, a 1-Lipschitz bound on the distance.
TALLOW_FN real meltFieldValue(pnanovdb_buf_t buf, real3 p, MeltShape m) {
  real3 d = p - m.anchor;
  real widen = sqrt(m.heightScale);
  real3 unslumped = m.anchor + real3(d.x * widen, d.y / m.heightScale, d.z * widen);
  real3 index = unslumped * m.invVoxel;
  // Far from every level's band the grids hold their background: skip the 8 or 16 tree reads
  // (most of a lattice that covers every t lies there).
  real body = m.background;
  if (!(any(lessThan(index, m.boxLo)) || any(greaterThan(index, m.boxHi)))) {
    body = meltGridSample(buf, m.gridA, index);
    if (m.blend > real(0)) body = mix(body, meltGridSample(buf, m.gridB, index), m.blend);
  }
  body = body * m.heightScale;
  if (!(m.puddleHeight > real(0))) return body;
  return meltSmoothUnion(body, meltPuddleDistance(p, m), m.joinRadius);
}
