// The melting candle's field, written once for GLSL and C++ (the conventions of
// shaders/bssrdf/real.glsl: `real`/`real3`, unsuffixed literals wrapped in real(), TALLOW_FN, no
// include guards, results as structs built member by member). Issue 16, points 2 and 3.
//
// Two parts, as the blob's (fields/blob.glsl):
//   candleShapeAt(s, params): the candle at s = t / duration ∈ [0, 1] — heights, the cup, the
//     drips' spheres — a few dozen numbers, evaluated once per frame on the CPU in double
//     (geometry::CandleField), handed to the GPU as the uniforms of fields/candle_uniforms.glsl;
//   candleField(p, shape): the signed distance at p and its analytic gradient, evaluated per
//     lattice sample on the GPU (fields/candle_lattice.comp), per vertex for the normals
//     (dual_contouring/vertices.geom with DC_CANDLE_NORMALS), and in double by CandleField::value
//     / gradient, so `tallow field`, `tallow mesh --cpu`, the CPU reference and the GPU agree.
//
// Until issue 16 the candle was an OpenVDB level set rebuilt for every t (cylinder mesh-to-volume,
// sphere chains csgUnion'ed, the bowl csgDifference'd, two mean-curvature steps, the wick), sampled
// on the CPU and uploaded. The issue proposes NanoVDB for "the initial candle's CSG"; but every part
// of the candle is a closed-form solid (cylinders, spheres, round cones), so the exact distance is
// cheaper to evaluate than a grid is to fetch, has no voxel error, no band to fill and nothing to
// upload, and its gradient is analytic: a grid is the answer for shapes that are not closed form
// (melting meshes: MeshLevelSetField, on NanoVDB). The positions and sizes are those of the old
// build(), so flamePosition, rimHeight, cupRadius and currentCupDepth keep their meaning:
//   wax    = rounded cylinder (radius, base y = 0, height h = height·(1 − burnFraction·s)),
//   drips  = each a swept sphere of radius dripRadius·(0.7 + 0.5u²) along the side, u ∈ [0, 1]
//            from its top to its bead (the old chain of spheres), as two round cones through
//            u = 0, 1/2, 1 (the chords of u²: radius within dripRadius/32 of the old one),
//   cup    = sphere of radius (cupR² + d²)/(2d) centred at y = h − d + bowlR, subtracted,
//            d = cupDepth·(0.35 + 0.65·smoothstep(0, 1/4, s)),
//   smooth = the drips joined to the wax and the cup cut with a quadratic smooth min/max of
//            radius k = smoothingIterations · voxelSize (2 voxels = 1 mm by default) and the
//            cylinder's edges rounded by k: what the two mean-curvature steps did (rounded rim,
//            blended drips),
//   wick   = cylinder (not smoothed) from 4 mm below the cup's bottom to wickLength above it.
// The result is clamped to ± the band (3 voxels), as the level set's values were outside its narrow
// band: far away the field reads ± band, which the tests and the lattice rely on, and the gradient
// there is 0.
//
// Distances are exact for every primitive; the smooth min/max is a bound (never farther than the
// true distance, gradient a convex combination of the two, so |∇| ≤ 1: 1-Lipschitz).
#ifdef TALLOW_GLSL
#include "common/shared.glsl"
#include "bssrdf/real.glsl"
#endif

const int CANDLE_MAX_DRIPS = 8;          // geometry::CandleParams::kMaxDrips
const int CANDLE_DRIP_SPHERES = 3;       // u = 0, 1/2, 1: two round cones per drip
const int CANDLE_MAX_SPHERES = CANDLE_MAX_DRIPS * CANDLE_DRIP_SPHERES;
const real CANDLE_BAND_VOXELS = 3.0;     // half-width of the clamp, voxels (the old narrow band)
const real CANDLE_DRIP_TOP_BELOW_RIM = 0.002;   // metres: a drip starts this far below the rim
const real CANDLE_WICK_ROOT_DEPTH = 0.004;      // metres: the wick's foot below the cup's bottom
const real CANDLE_PI = 3.14159265358979323846;

// The candle's constants (geometry::CandleParams, metres and seconds).
struct CandleParamsGlsl {
  real radius;
  real height;
  real burnFraction;
  real rimWidth;
  real cupDepth;
  real wickRadius;
  real wickLength;
  real flameLift;
  int dripCount;
  real dripRadius;
  real voxelSize;
  int smoothingIterations;
};

// The candle at one t: what candleField needs (the uniforms of fields/candle_uniforms.glsl).
struct CandleShape {
  real radius;       // wax cylinder
  real height;       // h(t): top of the cylinder, the top of the rim
  real cupRadius;    // where the cup meets the top
  real cupDepth;     // d(t), on the axis
  real bowlRadius;   // the sphere subtracted for the cup
  real bowlCentreY;
  real wickRadius;
  real wickBottom;
  real wickTop;
  real flameY;       // the flame (a point light) on the axis
  real smoothing;    // k: radius of the smooth min/max and of the cylinder's rounded edges
  real band;         // values are clamped to ± band
  real reach;        // the capped cylinder about the y axis that holds every part: radius,
  real low;          //   lowest and
  real high;         //   highest y
  int dripCount;     // drips that have started (each CANDLE_DRIP_SPHERES consecutive spheres)
  real3 dripCentre[CANDLE_MAX_SPHERES];
  real dripRadius[CANDLE_MAX_SPHERES];
};

// A signed distance (metres, negative inside) and its gradient.
struct CandleSdf {
  real d;
  real3 g;
};

TALLOW_FN CandleSdf candleSdf(real d, real3 g) {
  CandleSdf r;
  r.d = d;
  r.g = g;
  return r;
}

TALLOW_FN real candleSmoothstep(real a, real b, real x) {
  real u = clamp((x - a) / (b - a), real(0), real(1));
  return u * u * (real(3) - real(2) * u);
}

TALLOW_FN CandleShape candleShapeAt(real s, CandleParamsGlsl p) {
  CandleShape c;
  // Height burns down linearly; the cup forms quickly after lighting (a shallow dent at t = 0).
  c.radius = p.radius;
  c.height = p.height * (real(1) - p.burnFraction * s);
  c.cupDepth = p.cupDepth * (real(0.35) + real(0.65) * candleSmoothstep(real(0), real(0.25), s));
  c.cupRadius = p.radius - p.rimWidth;
  // The cup: a spherical bowl of depth d that meets the top at radius cupR, leaving the rim.
  c.bowlRadius = (c.cupRadius * c.cupRadius + c.cupDepth * c.cupDepth) / (real(2) * c.cupDepth);
  c.bowlCentreY = c.height - c.cupDepth + c.bowlRadius;
  real cupBottom = c.height - c.cupDepth;
  c.wickRadius = p.wickRadius;
  c.wickBottom = cupBottom - CANDLE_WICK_ROOT_DEPTH;
  c.wickTop = cupBottom + p.wickLength;
  c.flameY = cupBottom + p.wickLength + p.flameLift;
  c.smoothing = real(p.smoothingIterations) * p.voxelSize;
  c.band = CANDLE_BAND_VOXELS * p.voxelSize;
  for (int k = 0; k < CANDLE_MAX_SPHERES; ++k) {
    c.dripCentre[k] = real3(real(0));
    c.dripRadius[k] = real(0);
  }
  // Drips hugging the side, each starting at its own time and running down over 30% of the
  // animation to its own length, thickening into a bead at the bottom end.
  c.dripCount = 0;
  for (int i = 0; i < p.dripCount; ++i) {
    real start = real(0.08) + real(0.8) * real(i) / real(max(1, p.dripCount));
    real maxLength = p.height * (real(0.2) + real(0.06) * real((2 * i) % 3));
    real len = min(maxLength * candleSmoothstep(start, start + real(0.3), s), c.height - real(2) * p.dripRadius);
    if (len < p.dripRadius) continue;
    real angle = real(2) * CANDLE_PI * (real(0.11) + real(0.382) * real(i));
    real3 dir = real3(cos(angle), real(0), sin(angle));
    real top = c.height - CANDLE_DRIP_TOP_BELOW_RIM;
    for (int k = 0; k < CANDLE_DRIP_SPHERES; ++k) {
      real u = real(k) / real(CANDLE_DRIP_SPHERES - 1);
      real r = p.dripRadius * (real(0.7) + real(0.5) * u * u);
      int slot = CANDLE_DRIP_SPHERES * c.dripCount + k;
      c.dripCentre[slot] = (p.radius - real(0.2) * r) * dir + real3(real(0), top - u * len, real(0));
      c.dripRadius[slot] = r;
    }
    c.dripCount += 1;
  }
  // The round cones are the hulls of their spheres, so the spheres bound them.
  c.reach = c.radius;
  c.low = real(0);
  for (int k = 0; k < CANDLE_DRIP_SPHERES * c.dripCount; ++k) {
    c.reach = max(c.reach, length(real2(c.dripCentre[k].x, c.dripCentre[k].z)) + c.dripRadius[k]);
    c.low = min(c.low, c.dripCentre[k].y - c.dripRadius[k]);
  }
  c.high = max(c.height, c.wickTop);
  return c;
}

// --- primitives ---------------------------------------------------------------------------------

TALLOW_FN CandleSdf candleSphere(real3 p, real3 centre, real r) {
  real3 q = p - centre;
  real l = length(q);
  return candleSdf(l - r, l > real(0) ? q / l : real3(real(0)));
}

// Capped cylinder of radius r about the y axis from y0 to y1: the distance in the (radial, axial)
// plane to the rectangle [0, r] × [y0, y1].
TALLOW_FN CandleSdf candleCylinder(real3 p, real r, real y0, real y1) {
  real rho = length(real2(p.x, p.z));
  real3 radial = rho > real(0) ? real3(p.x / rho, real(0), p.z / rho) : real3(real(0));
  real e = rho - r;
  real lower = y0 - p.y, upper = p.y - y1;
  real f = max(lower, upper);
  real3 axial = upper > lower ? real3(real(0), real(1), real(0)) : real3(real(0), real(-1), real(0));
  if (e > real(0) && f > real(0)) {
    real l = length(real2(e, f));
    return candleSdf(l, (e / l) * radial + (f / l) * axial);
  }
  if (e > f) return candleSdf(e, radial);
  return candleSdf(f, axial);
}

// Round cone: the convex hull of the spheres (a, ra) and (b, rb), i.e. the sphere swept from a to b
// with its radius interpolated linearly. In the plane of the axis and p, with x along the axis from
// a and y ≥ 0 across it, the side is the common tangent of the two circles; its outward normal
// n = (sin θ, cos θ) with sin θ = (ra − rb)/|b − a| touches circle a at ra·n and circle b at
// (|b − a|, 0) + rb·n, and the side runs along τ = (cos θ, −sin θ) for |b − a|·cos θ. A point whose
// projection on τ falls before the side is nearest sphere a, after it sphere b, else the side.
TALLOW_FN CandleSdf candleRoundCone(real3 p, real3 a, real ra, real3 b, real rb) {
  real3 ba = b - a;
  real l = length(ba);
  if (l <= abs(ra - rb)) {  // one sphere holds the other
    if (ra > rb) return candleSphere(p, a, ra);
    return candleSphere(p, b, rb);
  }
  real3 w = ba / l;
  real3 q = p - a;
  real x = dot(q, w);
  real3 across = q - x * w;
  real y = length(across);
  real sinT = (ra - rb) / l;
  real cosT = sqrt(real(1) - sinT * sinT);
  real along = x * cosT - y * sinT;
  if (along < real(0)) return candleSphere(p, a, ra);
  if (along > l * cosT) return candleSphere(p, b, rb);
  real3 radial = y > real(0) ? across / y : real3(real(0));
  return candleSdf(x * sinT + y * cosT - ra, sinT * w + cosT * radial);
}

// Quadratic smooth minimum of radius k (k > 0): mix(b, a, h) − k·h(1 − h) with
// h = clamp(1/2 + (b − a)/(2k), 0, 1); equal to min(a, b) where |a − b| ≥ k and at most k/4 below
// it. Its derivative in h vanishes where 0 < h < 1 (there a − b = k(1 − 2h)), so its gradient is
// h·∇a + (1 − h)·∇b exactly.
TALLOW_FN CandleSdf candleSmoothUnion(CandleSdf a, CandleSdf b, real k) {
  if (!(k > real(0))) {
    if (a.d < b.d) return a;
    return b;
  }
  real h = clamp(real(0.5) + real(0.5) * (b.d - a.d) / k, real(0), real(1));
  return candleSdf(mix(b.d, a.d, h) - k * h * (real(1) - h), h * a.g + (real(1) - h) * b.g);
}

// a minus b, smoothed: −smoothUnion(−a, b).
TALLOW_FN CandleSdf candleSmoothSubtract(CandleSdf a, CandleSdf b, real k) {
  CandleSdf u = candleSmoothUnion(candleSdf(-a.d, -a.g), b, k);
  return candleSdf(-u.d, -u.g);
}

// --- the candle ---------------------------------------------------------------------------------

// The candle's signed distance at p (metres, negative inside) clamped to ± band, and its gradient
// (0 where clamped).
TALLOW_FN CandleSdf candleField(real3 p, CandleShape c) {
  real k = c.smoothing;
  // Two early outs that return what the full evaluation below returns, skipping the drips (most
  // lattice samples are beyond the band). The smooth min lies at most k/4 below the min, the smooth
  // max at most k/4 above the max, so: (1) every part lies in the cylinder (reach, low, high), so
  // the field is at least the distance to it − k/4 and clamps to +band where that is ≥ band;
  // (2) where the wax cylinder is below −(band + k/4) and the bowl above band + k/4, the cup's
  // smooth max is at most −band and the drips and the wick only lower it: −band.
  real slack = c.band + real(0.25) * k;
  if (candleCylinder(p, c.reach, c.low, c.high).d >= slack) return candleSdf(c.band, real3(real(0)));
  CandleSdf wax = candleCylinder(p, c.radius - k, k, c.height - k);
  wax.d -= k;  // edges rounded by k, outer size unchanged
  CandleSdf bowl = candleSphere(p, real3(real(0), c.bowlCentreY, real(0)), c.bowlRadius);
  if (wax.d <= -slack && bowl.d >= slack) return candleSdf(-c.band, real3(real(0)));
  for (int i = 0; i < c.dripCount; ++i) {
    int s = CANDLE_DRIP_SPHERES * i;
    CandleSdf drip = candleRoundCone(p, c.dripCentre[s], c.dripRadius[s], c.dripCentre[s + 1], c.dripRadius[s + 1]);
    CandleSdf bead = candleRoundCone(p, c.dripCentre[s + 1], c.dripRadius[s + 1], c.dripCentre[s + 2], c.dripRadius[s + 2]);
    if (bead.d < drip.d) drip = bead;
    wax = candleSmoothUnion(wax, drip, k);
  }
  wax = candleSmoothSubtract(wax, bowl, k);
  CandleSdf wick = candleCylinder(p, c.wickRadius, c.wickBottom, c.wickTop);
  if (wick.d < wax.d) wax = wick;
  if (wax.d >= c.band) return candleSdf(c.band, real3(real(0)));
  if (wax.d <= -c.band) return candleSdf(-c.band, real3(real(0)));
  return wax;
}

TALLOW_FN real candleFieldValue(real3 p, CandleShape c) { return candleField(p, c).d; }
TALLOW_FN real3 candleFieldGradient(real3 p, CandleShape c) { return candleField(p, c).g; }
