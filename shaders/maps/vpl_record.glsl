// A VPL as maps/vpl.comp writes it and the receivers read it (sss::VplRecord, 48 bytes):
// position (x_v [m], η; η 0: inactive), normal (n_v, A_v [m²]), radiance (B(x_v)/π, shadow cluster).
struct VplGpu { vec4 position; vec4 normal; vec4 radiance; };

// Directions uniform over the sphere from c put surface points at density cos α / (4π |r|² N) per
// unit area (α between n_v and x_v − c); a VPL seen more obliquely than this from c is capped,
// against single VPLs of unbounded area at silhouettes seen edge-on.
const float VPL_MIN_COS_ALPHA = 0.1;

// A unit vector perpendicular to the unit vector n: a tangent for a VPL's frame.
vec3 vplPerpendicular(vec3 n) {
  return normalize(abs(n.y) < 0.9 ? cross(vec3(0.0, 1.0, 0.0), n) : cross(vec3(1.0, 0.0, 0.0), n));
}

// Each VPL's solid-angle cell is also split into VPL_PART_SIDE² parts, records of the same layout
// (a part's area is its share of A_v), which a receiver near the VPL uses instead of the VPL: the
// surface's own positions, normals and B inside the cell rather than one patch of one radiance.
// 3 × 3 measured as 4 × 4 on the candle holder and the candle, 2 × 2 worse (docs/vpl.md).
const int VPL_PART_SIDE = 3;
const int VPL_PARTS = VPL_PART_SIDE * VPL_PART_SIDE;
