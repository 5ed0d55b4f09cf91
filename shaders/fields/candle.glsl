// The melting candle's field, written once for GLSL and C++ (the conventions of
// shaders/bssrdf/real.glsl: `real`/`real2`/`real3`, unsuffixed literals wrapped in real(), TALLOW_FN,
// no include guards, results as structs built member by member). Issue 16 (closed form, GPU) and
// issue 35 (a melt model: a pool, a rim, drips that freeze, a puddle, volume conserved).
//
// Two parts, as the blob's (fields/blob.glsl):
//   candleShapeAt(t, params): the candle at animation time t — its outline, the pool, the notches,
//     the drips' spheres, the puddle's lobes — evaluated once per frame on the CPU in double
//     (geometry::CandleField), handed to the GPU as the uniforms of fields/candle_uniforms.glsl.
//     Every t is computed from t alone (no state is carried from frame to frame), so scrubbing,
//     `tallow mesh --time T` and playback agree;
//   candleField(p, shape): the signed distance at p and its analytic gradient, evaluated per
//     lattice sample on the GPU (fields/lattice.comp), per vertex for the normals
//     (dual_contouring/vertices.geom with DC_CANDLE_NORMALS), and in double by CandleField::value /
//     gradient, so `tallow field`, `tallow mesh --cpu`, the CPU reference and the GPU agree.
//
// The model (docs/presets.md gives the sources of its numbers), in animation seconds t; the preset's
// time scale says how many real seconds one of them stands for:
//   burn    the flame consumes wax at a constant volume rate (its mass burning rate over the wax's
//           density): the candle's volume is V0 − rate·t, and that volume is conserved between the
//           solid, the liquid pool, the drips and the puddle — the hollow's depth and then the rim's
//           height are solved from it (candleTopFor), not set: the rim stands at its first height
//           while the flame carves the hollow, and comes down once the hollow has its full depth;
//   pool    liquid wax around the wick under a flat, horizontal free surface at h − Δ(t): its radius
//           grows from the wick toward the wall, r_p(t) = r_w + (r_max − r_w)(1 − e^(−t/τ)), τ a third
//           of the real time a full melt pool takes (a candle-maker's hour per inch of diameter),
//           r_max leaving an eighth of an inch of wall; its depth on the axis grows likewise; while it
//           is narrow the hollow above it is a tunnel;
//   rim     the wall standing Δ(t) above the pool (a hollowed pillar, Δ at most its full depth
//           Δ_full·(1 − e^(−1.5t/τ)), as deep as the burnt volume allows), thinning toward its top: the
//           inside of the wall is r = r_p + (r_top − r_p)·u² with u from 0 at the pool to 1 at the
//           top, so the top few millimetres are a thin lip (the glowing wall of a lit candle);
//   drips   once the pool is wide (r_p ≥ overflowStart·r_max) the pool overflows now and then, at
//           times and places drawn from the preset's seed: the rim is notched there and a drip runs
//           down the outer wall, slowing as it cools (its length L(τ) = L_max·(1 − (1 − τ/τ_run)²)),
//           thickening into a bead at its lower end, and from τ_run on it is frozen: nothing of it
//           moves while the top burns down past it (the top clips it); a drip may run over another;
//   puddle  a drip long enough to reach the table stops there and feeds a puddle at its foot, whose
//           volume grows as V_f·(1 − e^(−(τ − τ_hit)/τ_feed)): a flat disc with a rounded edge.
// Sizes are metres. The wax's outline (cylinder, rounded edges, the hollow above the pool, the flat
// pool surface, a meniscus where it meets the wall) is one polygon in the (radius, height) half-plane
// revolved about the axis: its exact distance is the 2D distance to the polygon, and its volume the
// sum of the frusta its edges sweep (Pappus). Drips are round cones (the hull of two spheres), the
// puddle's lobes flat-bottomed pucks, the notches spheres cut away; they are joined with a smooth
// min/max of radius k (smoothingIterations voxels). The result is clamped to ± the band (3 voxels).
// Distances are exact for every primitive; the smooth min/max is a bound (never farther than the
// true distance, gradient a convex combination of the two, so |∇| ≤ 1: 1-Lipschitz).
#ifdef TALLOW_GLSL
#include "common/shared.glsl"
#include "bssrdf/real.glsl"
#endif

const int CANDLE_MAX_DRIPS = 12;         // geometry::CandleParams::kMaxDrips
const int CANDLE_DRIP_SPHERES = 7;       // a drip: its source in the notch, over the edge, 5 down the wall (the last the bead)
const int CANDLE_MAX_SPHERES = CANDLE_MAX_DRIPS * CANDLE_DRIP_SPHERES;
const int CANDLE_PROFILE_POINTS = 48;    // the outline's vertices, at most
const int CANDLE_ARC_STEPS = 8;         // segments per rounded edge (a quarter circle): creases of 11°
const real CANDLE_BAND_VOXELS = 3.0;     // half-width of the clamp, voxels
const real CANDLE_WICK_ROOT_DEPTH = 0.002;  // metres: the wick's foot below the pool's deepest point
const real CANDLE_NOTCH_RADIUS = 0.0025;    // metres: the sphere an overflow cuts from the rim
const real CANDLE_NOTCH_DEPTH = 0.0012;     // metres: how far below the rim's top the notch reaches
const real CANDLE_MENISCUS = 0.0008;        // metres: radius of the fillet where the pool meets the wall
// A drip's axis lies this many of its radii inside the wall: it stands out by 0.7 of its radius and
// is as wide as 1.9 radii where it meets the wall, a flattened run rather than a round cord.
const real CANDLE_DRIP_IN = 0.3;
const real CANDLE_PI = 3.14159265358979323846;

// The candle's constants in animation time (geometry::CandleParams converts the physical ones).
struct CandleParamsGlsl {
  real radius;          // wax cylinder
  real height;          // at t = 0 (base at y = 0)
  real burnRate;        // m³ of wax the flame consumes per animation second
  real poolTau;         // animation seconds: the pool's radius and depth approach their full size as 1 − e^(−t/τ)
  real poolWall;        // wall left at the pool's level once it is full
  real poolDepth;       // liquid depth on the axis once full
  real rimAbovePool;    // Δ once the hollow has formed
  real lip;             // the rim's thickness at its top once the pool is full
  real wickRadius;
  real wickExposed;     // wick above the pool
  real flameLift;       // the flame's emission centre above the wick's tip
  int dripCount;        // overflows over the animation (≤ CANDLE_MAX_DRIPS)
  real dripRadius;
  real dripRun;         // animation seconds a drip runs before it freezes (mean)
  real overflowStart;   // share of the pool's full radius from which it overflows
  real overflowEnd;     // animation time by which every overflow has happened
  real puddleThickness;
  real puddleFeed;      // m³ a drip that reaches the table feeds into its puddle, in the end
  real puddleFeedTau;   // animation seconds
  int seed;
  real voxelSize;
  int smoothingIterations;
};

// The candle at one t: what candleField needs (the uniforms of fields/candle_uniforms.glsl), and
// what the tests and RESULTS measure of it.
struct CandleShape {
  real radius;       // wax cylinder
  real height;       // h(t): the rim's top
  real poolY;        // the pool's free surface
  real poolRadius;   // r_p(t)
  real poolDepth;    // liquid depth on the axis
  real wickRadius;
  real wickBottom;
  real wickTop;
  real flameY;       // the flame (a point light) on the axis
  real smoothing;    // k: radius of the smooth min/max
  real band;         // values are clamped to ± band
  real reach;        // the capped cylinder about the y axis that holds every part: radius,
  real low;          //   lowest and
  real high;         //   highest y
  // Arrays of four-vectors (each element one uniform slot on the GPU, the budget a 4.5 context
  // guarantees: 1024 components):
  int profileCount;
  real4 profile[CANDLE_PROFILE_POINTS / 2];  // point 2i in (x, y), 2i + 1 in (z, w): (radius, y),
                                             // counter-clockwise; the last to the first runs along the axis
  int notchCount;
  real4 notch[CANDLE_MAX_DRIPS];             // xyz: the centre of a sphere of CANDLE_NOTCH_RADIUS cut away
  real dripClipY;    // drips end below this (the top has burnt past what was above)
  int dripCount;     // drips that have started (each CANDLE_DRIP_SPHERES consecutive spheres)
  real4 drip[CANDLE_MAX_SPHERES];            // xyz: a sphere's centre, w: its radius
  real4 dripBound[CANDLE_MAX_DRIPS];         // a sphere holding each drip, for an early out
  int puddleCount;
  real4 puddle[CANDLE_MAX_DRIPS];            // xyz: a lobe's centre on the table (y = 0), w: its radius
  real puddleThickness;
  // Measured, not uploaded:
  real volumeTarget;   // V0 − burnt: what the wax must hold
  real volumeDrips;    // outside the cylinder
  real volumePuddle;   // outside the cylinder
  real puddleArea;     // footprint outside the cylinder, m²
  int dripsFrozen;
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

// --- deterministic draws -----------------------------------------------------------------------

// A number in [0, 1) from the preset's seed, a drip's index and what is drawn (an integer hash,
// Jenkins' finaliser style: the same on every machine, in GLSL and C++).
TALLOW_FN real candleDraw(int seed, int index, int what) {
  uint h = uint(seed) * 747796405u + uint(index) * 2891336453u + uint(what) * 277803737u + 1013904223u;
  h = h ^ (h >> 16u);
  h = h * 2246822519u;
  h = h ^ (h >> 13u);
  h = h * 3266489917u;
  h = h ^ (h >> 16u);
  return real(h) / real(4294967296.0);
}

// --- the model's functions of t (CPU only, in double) ----------------------------------------

// 1 − e^(−t/τ): how far the pool is toward its full size.
TALLOW_FN real candlePoolGrowth(real t, CandleParamsGlsl p) { return real(1) - exp(-max(t, real(0)) / p.poolTau); }

TALLOW_FN real candlePoolRadiusAt(real t, CandleParamsGlsl p) {
  real start = real(3) * p.wickRadius;
  return start + (p.radius - p.poolWall - start) * candlePoolGrowth(t, p);
}

// The hollow above the pool forms a little faster than the pool widens (the flame heats the wax
// beside it first).
TALLOW_FN real candleHollowAt(real t, CandleParamsGlsl p) {
  return p.rimAbovePool * (real(1) - exp(real(-1.5) * max(t, real(0)) / p.poolTau));
}

// The inside of the wall at the rim's top: most of the way from the pool's edge to the lip.
TALLOW_FN real candleTopInnerAt(real poolRadius, CandleParamsGlsl p) {
  return poolRadius + real(0.75) * max(p.radius - p.lip - poolRadius, real(0));
}

// When overflow k happens (animation seconds), and where (radians about the axis). The first comes
// when the pool reaches overflowStart of its full width, the rest at drawn gaps up to overflowEnd.
TALLOW_FN real candleOverflowStart(CandleParamsGlsl p) {
  // r_p = start + (max − start)(1 − e^(−t/τ)) reaches start + share·(max − start) at t = −τ ln(1 − share).
  return -p.poolTau * log(max(real(1) - p.overflowStart, real(1e-6)));
}

TALLOW_FN real candleOverflowTime(int k, CandleParamsGlsl p) {
  real first = candleOverflowStart(p);
  real span = max(p.overflowEnd - first, real(0));
  // Gaps of drawn length, normalised so that the last overflow lands within the span.
  real total = real(0), before = real(0);
  for (int j = 0; j < CANDLE_MAX_DRIPS; ++j) {
    if (j >= p.dripCount) break;
    real gap = real(0.35) + candleDraw(p.seed, j, 0);
    total += gap;
    if (j < k) before += gap;
  }
  return first + span * before / max(total, real(1e-9));
}

TALLOW_FN real candleOverflowAngle(int k, CandleParamsGlsl p) { return real(2) * CANDLE_PI * candleDraw(p.seed, k, 1); }

// A drip's whole intended length as a share of the height it starts at: most stop part way down,
// about a third reach the table (share ≥ 1).
TALLOW_FN real candleDripReach(int k, CandleParamsGlsl p) {
  real u = candleDraw(p.seed, k, 2);
  if (u < real(0.35)) return real(1.2);
  return real(0.2) + real(0.6) * candleDraw(p.seed, k, 3);
}

TALLOW_FN real candleDripRunTime(int k, CandleParamsGlsl p) { return p.dripRun * (real(0.7) + real(0.6) * candleDraw(p.seed, k, 4)); }

// How far along its run a drip is after τ (x = τ / run): decelerating, at rest from x = 1.
TALLOW_FN real candleRunShare(real x) {
  real c = clamp(x, real(0), real(1));
  return real(1) - (real(1) - c) * (real(1) - c);
}

// Area of the lens where two discs of radii a and b, centres d apart, overlap.
TALLOW_FN real candleLensArea(real a, real b, real d) {
  if (d >= a + b) return real(0);
  if (d <= abs(a - b)) return CANDLE_PI * min(a, b) * min(a, b);
  real ca = clamp((d * d + a * a - b * b) / (real(2) * d * a), real(-1), real(1));
  real cb = clamp((d * d + b * b - a * a) / (real(2) * d * b), real(-1), real(1));
  real k = (-d + a + b) * (d + a - b) * (d - a + b) * (d + a + b);
  return a * a * acos(ca) + b * b * acos(cb) - real(0.5) * sqrt(max(k, real(0)));
}

// The share of a disc of radius r centred c from the axis that lies outside the candle (radius R).
TALLOW_FN real candleOutsideShare(real r, real c, real R) {
  return real(1) - candleLensArea(r, R, c) / (CANDLE_PI * r * r);
}

// The volume of a puddle lobe of footprint radius ρ and thickness e (a flat-bottomed puck: a disc
// of radius ρ − e swept by a ball of radius e, its lower half cut by the table), by Pappus.
TALLOW_FN real candlePuckVolume(real rho, real e) {
  real inner = max(rho - e, real(0));
  return CANDLE_PI * inner * inner * e + real(0.5) * CANDLE_PI * CANDLE_PI * e * e * inner +
         real(2) / real(3) * CANDLE_PI * e * e * e;
}

// Where a lobe of radius ρ sits: its centre this far from the axis, wrapped partly round the foot.
TALLOW_FN real candlePuddleOffset(real rho, real R) { return R + real(0.55) * rho; }

// The lobe whose volume outside the candle is v (Newton on ρ; the volume grows with ρ).
TALLOW_FN real candlePuddleRadius(real v, real R, real e) {
  if (!(v > real(0))) return real(0);
  real rho = sqrt(v / (CANDLE_PI * e)) + e;
  for (int i = 0; i < 24; ++i) {
    real c = candlePuddleOffset(rho, R);
    real f = candlePuckVolume(rho, e) - candleLensArea(rho, R, c) * e - v;
    real h = real(1e-6) * max(rho, real(1e-4));
    real c2 = candlePuddleOffset(rho + h, R);
    real f2 = candlePuckVolume(rho + h, e) - candleLensArea(rho + h, R, c2) * e - v;
    real slope = (f2 - f) / h;
    if (!(slope > real(0))) break;
    rho = max(rho - f / slope, real(0.5) * e);
  }
  return rho;
}

// The outline at rim height h: the wax as a polygon in (radius, height), counter-clockwise from the
// axis at the base; the closing edge runs down the axis (no surface there).
struct CandleOutline {
  int count;
  real2 points[CANDLE_PROFILE_POINTS];
};

TALLOW_FN CandleOutline candleOutlineAdd(CandleOutline o, real2 q) {
  if (o.count < CANDLE_PROFILE_POINTS) {
    o.points[o.count] = q;
    o.count += 1;
  }
  return o;
}

// A quarter arc about `centre` of radius r from angle a0 to a1 (radians), `steps` points after the first.
TALLOW_FN CandleOutline candleOutlineArc(CandleOutline o, real2 centre, real r, real a0, real a1, int steps) {
  for (int i = 1; i <= steps; ++i) {
    real a = a0 + (a1 - a0) * real(i) / real(steps);
    o = candleOutlineAdd(o, centre + r * real2(cos(a), sin(a)));
  }
  return o;
}

TALLOW_FN CandleOutline candleOutlineAt(real h, real poolY, real poolRadius, real topInner, real k, CandleParamsGlsl p) {
  real R = p.radius;
  real halfPi = real(0.5) * CANDLE_PI;
  CandleOutline o;
  o.count = 0;
  for (int i = 0; i < CANDLE_PROFILE_POINTS; ++i) o.points[i] = real2(real(0));
  o = candleOutlineAdd(o, real2(real(0), real(0)));
  // The base's edge, rounded by k.
  o = candleOutlineAdd(o, real2(R - k, real(0)));
  o = candleOutlineArc(o, real2(R - k, k), k, -halfPi, real(0), CANDLE_ARC_STEPS);
  real hollow = h - poolY;
  // The rim's top: its outer and inner edges rounded by up to k, as the lip's width and the hollow allow.
  real a = min(k, min(real(0.5) * (R - topInner), real(0.45) * hollow));
  a = max(a, real(1e-5));
  o = candleOutlineAdd(o, real2(R, h - a));
  o = candleOutlineArc(o, real2(R - a, h - a), a, real(0), halfPi, CANDLE_ARC_STEPS);
  o = candleOutlineAdd(o, real2(topInner + a, h));
  o = candleOutlineArc(o, real2(topInner + a, h - a), a, halfPi, CANDLE_PI, CANDLE_ARC_STEPS);
  // Down the inside of the wall, r = r_p + (r_top − r_p)·u², to the meniscus.
  real m = min(CANDLE_MENISCUS, min(real(0.4) * max(hollow - a, real(0)), real(0.5) * poolRadius));
  real wallTop = h - a;
  real span = max(wallTop - (poolY + m), real(0));
  for (int i = 1; i <= 6; ++i) {
    real u = real(1) - real(i) / real(6);
    real y = poolY + m + span * u;
    real r = poolRadius + (topInner - poolRadius) * u * u;
    if (i < 6 || m > real(1e-6)) o = candleOutlineAdd(o, real2(r, y));
  }
  // The meniscus: a concave fillet of radius m from the wall onto the pool's surface.
  if (m > real(1e-6)) o = candleOutlineArc(o, real2(poolRadius - m, poolY + m), m, real(0), -halfPi, CANDLE_ARC_STEPS);
  // Across the pool's flat surface to the axis.
  o = candleOutlineAdd(o, real2(real(0), poolY));
  return o;
}

// The volume the outline sweeps about the axis: Σ over its edges of (π/3)(r_i² + r_i r_j + r_j²)(y_j − y_i).
TALLOW_FN real candleOutlineVolume(CandleOutline o) {
  real v = real(0);
  for (int i = 0; i < CANDLE_PROFILE_POINTS; ++i) {
    if (i >= o.count) break;
    real2 a = o.points[i];
    real2 b = o.points[(i + 1) % o.count];
    v += (a.x * a.x + a.x * b.x + b.x * b.x) * (b.y - a.y);
  }
  return CANDLE_PI / real(3) * v;
}

// The volume of a round cone's tube between spheres (a, ra) and (b, rb) as a frustum, of the part
// below y = clip, outside the candle (its axis about c from the candle's).
TALLOW_FN real candleTubeVolume(real3 a, real ra, real3 b, real rb, real clip, real R) {
  real len = length(b - a);
  real frustum = CANDLE_PI / real(3) * len * (ra * ra + ra * rb + rb * rb);
  real top = max(a.y, b.y), bottom = min(a.y, b.y);
  real below = top > bottom ? clamp((clip - bottom) / (top - bottom), real(0), real(1)) : (clip > top ? real(1) : real(0));
  real r = real(0.5) * (ra + rb);
  real c = length(real2(real(0.5) * (a.x + b.x), real(0.5) * (a.z + b.z)));
  return frustum * below * candleOutsideShare(r, c, R);
}

// One drip at time t: its five spheres into `shape` (slot `slot`), and its volume and puddle.
struct CandleDrip {
  real3 centre[CANDLE_DRIP_SPHERES];
  real radius[CANDLE_DRIP_SPHERES];
  real volume;        // outside the candle, below the clip
  real puddleVolume;  // fed into the puddle at its foot (0 unless it reached the table)
  real3 foot;         // where its bead rests
  bool frozen;
};

// Drip k at time t, started at `start` from a rim of height `rimAtStart` whose inside was
// `innerAtStart` from the axis, clipped at `clip`.
TALLOW_FN CandleDrip candleDripAt(int k, real t, real start, real rimAtStart, real innerAtStart, real clip,
                                  CandleParamsGlsl p) {
  CandleDrip d;
  real R = p.radius;
  real rd = p.dripRadius * (real(0.8) + real(0.4) * candleDraw(p.seed, k, 5));
  real angle = candleOverflowAngle(k, p);
  real3 dir = real3(cos(angle), real(0), sin(angle));
  real y0 = rimAtStart - CANDLE_NOTCH_DEPTH;
  real tau = t - start;
  real run = candleDripRunTime(k, p);
  real below = real(0.0006);  // the edge: the drip turns down a little under the notch
  real room = max(y0 - below - real(1.1) * rd, real(0));  // down to the bead resting on the table
  real wanted = candleDripReach(k, p) * y0;
  real full = min(wanted, room);
  real share = candleRunShare(tau / run);
  real length_ = wanted * share;
  bool hit = wanted > room;
  real hitShare = hit ? room / wanted : real(1);
  // The time it reaches the table: wanted·(1 − (1 − x)²) = room.
  real hitX = hit ? real(1) - sqrt(max(real(1) - hitShare, real(0))) : real(1);
  length_ = min(length_, full);
  d.frozen = tau >= (hit ? hitX * run : run);
  // The bead grows as the drip runs, thickest where it stopped.
  real grow = clamp(length_ / real(0.006), real(0), real(1));
  // Its path down the wall wanders sideways (drawn per drip) and its thickness varies along it.
  real wander = (candleDraw(p.seed, k, 6) - real(0.5)) * real(0.12);  // radians at its end
  real wiggle = (candleDraw(p.seed, k, 7) - real(0.5)) * real(0.05);  // radians, one bend
  real phase = real(2) * CANDLE_PI * candleDraw(p.seed, k, 8);
  real rim = real(0.5) * (R + innerAtStart);
  d.centre[0] = rim * dir + real3(real(0), y0 - real(0.2) * rd, real(0));
  d.radius[0] = real(0.7) * rd;
  d.centre[1] = (R + real(0.1) * rd) * dir + real3(real(0), y0 - below, real(0));
  d.radius[1] = rd;
  for (int i = 2; i < CANDLE_DRIP_SPHERES; ++i) {
    real u = real(i - 1) / real(CANDLE_DRIP_SPHERES - 2);
    bool bead = i + 1 == CANDLE_DRIP_SPHERES;
    real swell = real(0.12) * sin(real(7) * u + phase);
    real r = bead ? rd * (real(1.05) + real(0.5) * grow) : rd * (real(0.9) + real(0.15) * u + swell);
    real a = angle + wander * u * u + wiggle * sin(real(3.3) * u * CANDLE_PI + phase);
    real3 along = real3(cos(a), real(0), sin(a));
    // The bead sits on the wall's surface rather than in it.
    real offset = bead ? real(0.1) : -CANDLE_DRIP_IN;
    d.centre[i] = (R + offset * r) * along + real3(real(0), y0 - below - length_ * u, real(0));
    d.radius[i] = r;
  }
  d.volume = real(0);
  for (int i = 0; i + 1 < CANDLE_DRIP_SPHERES; ++i)
    d.volume += candleTubeVolume(d.centre[i], d.radius[i], d.centre[i + 1], d.radius[i + 1], clip, R);
  // The caps at the two ends (halves of their spheres), the bead's outside the candle.
  real bead = d.radius[CANDLE_DRIP_SPHERES - 1];
  d.volume += real(2) / real(3) * CANDLE_PI * bead * bead * bead *
              candleOutsideShare(bead, R + real(0.1) * bead, R);
  d.foot = d.centre[CANDLE_DRIP_SPHERES - 1];
  d.puddleVolume = real(0);
  if (hit) {
    real since = tau - hitX * run;
    if (since > real(0)) d.puddleVolume = p.puddleFeed * (real(1) - exp(-since / p.puddleFeedTau));
  }
  return d;
}

// The rim's height and the hollow's depth at time t, `extra` the volume outside the outline (drips,
// puddles, the wick, less the notches): the volume is conserved,
//   V_outline(h, Δ) + extra = V0 − rate·t.
// While the hollow is still being carved the rim stands at its first height and the hollow's depth
// Δ ≤ Δ_full(t) is what the burnt volume leaves (bisection: V_outline falls as Δ grows); once the
// hollow has its full depth the rim comes down, and h follows in closed form (V_outline is linear
// in h for a fixed hollow).
struct CandleTop {
  real height;
  real hollow;
};

TALLOW_FN CandleTop candleTopFor(real t, real extra, CandleParamsGlsl p) {
  real R = p.radius;
  real poolRadius = candlePoolRadiusAt(t, p);
  real full = candleHollowAt(t, p);
  real topInner = candleTopInnerAt(poolRadius, p);
  // The outline's roundings are part of its volume: it is evaluated with them.
  real k = real(p.smoothingIterations) * p.voxelSize;
  real target = CANDLE_PI * R * R * p.height - p.burnRate * max(t, real(0)) - extra;
  real h1 = p.height, h2 = real(0.5) * p.height;
  real v1 = candleOutlineVolume(candleOutlineAt(h1, h1 - full, poolRadius, topInner, k, p));
  real v2 = candleOutlineVolume(candleOutlineAt(h2, h2 - full, poolRadius, topInner, k, p));
  CandleTop top;
  top.height = h1 + (target - v1) / ((v1 - v2) / (h1 - h2));
  top.hollow = full;
  if (top.height <= h1) return top;
  // Still carving: the rim at its first height, the hollow as deep as the burnt volume allows.
  real lo = real(0), hi = full;
  for (int i = 0; i < 48; ++i) {
    real mid = real(0.5) * (lo + hi);
    real v = candleOutlineVolume(candleOutlineAt(h1, h1 - mid, poolRadius, topInner, k, p));
    if (v > target) lo = mid;
    else hi = mid;
  }
  top.height = h1;
  top.hollow = real(0.5) * (lo + hi);
  return top;
}

TALLOW_FN CandleShape candleShapeAt(real t, CandleParamsGlsl p) {
  CandleShape c;
  real R = p.radius;
  t = max(t, real(0));
  c.radius = R;
  c.smoothing = real(p.smoothingIterations) * p.voxelSize;
  c.band = CANDLE_BAND_VOXELS * p.voxelSize;
  c.poolRadius = candlePoolRadiusAt(t, p);
  c.poolDepth = p.poolDepth * candlePoolGrowth(t, p);
  c.wickRadius = p.wickRadius;
  c.puddleThickness = p.puddleThickness;
  real topInner = candleTopInnerAt(c.poolRadius, p);
  real wickVolume = CANDLE_PI * p.wickRadius * p.wickRadius * p.wickExposed;
  real notchVolume = real(0.5) * CANDLE_NOTCH_DEPTH * CANDLE_NOTCH_DEPTH * CANDLE_NOTCH_RADIUS * CANDLE_PI;
  for (int i = 0; i < CANDLE_MAX_SPHERES; ++i) c.drip[i] = real4(real(0));
  for (int i = 0; i < CANDLE_MAX_DRIPS; ++i) {
    c.notch[i] = real4(real(0));
    c.dripBound[i] = real4(real(0));
    c.puddle[i] = real4(real(0));
  }
  // The overflows that have happened, in order: each one's start height needs the rim's height
  // at its time, which the earlier ones' volumes lower.
  real rimAt[CANDLE_MAX_DRIPS];
  real innerAt[CANDLE_MAX_DRIPS];
  real startAt[CANDLE_MAX_DRIPS];
  int started = 0;
  for (int k = 0; k < CANDLE_MAX_DRIPS; ++k) {
    rimAt[k] = real(0);
    innerAt[k] = real(0);
    startAt[k] = real(0);
    if (k >= p.dripCount) continue;
    real tk = candleOverflowTime(k, p);
    if (tk > t) continue;
    // The rim's height at t_k with the drips before it (clipped at the rim itself, within a few
    // fixed-point steps: the clip removes little).
    real hk = candleTopFor(tk, wickVolume, p).height;
    for (int it = 0; it < 3; ++it) {
      real extra = wickVolume;
      for (int j = 0; j < k; ++j) {
        CandleDrip dj = candleDripAt(j, tk, startAt[j], rimAt[j], innerAt[j], hk, p);
        extra += dj.volume + dj.puddleVolume - notchVolume;
      }
      hk = candleTopFor(tk, extra, p).height;
    }
    rimAt[k] = hk;
    innerAt[k] = candleTopInnerAt(candlePoolRadiusAt(tk, p), p);
    startAt[k] = tk;
    started = k + 1;
  }
  // The rim's height now, with every drip and puddle so far.
  CandleTop top = candleTopFor(t, wickVolume, p);
  real drips = real(0), puddle = real(0);
  for (int it = 0; it < 4; ++it) {
    drips = real(0);
    puddle = real(0);
    for (int k = 0; k < CANDLE_MAX_DRIPS; ++k) {
      if (k >= started) break;
      CandleDrip d = candleDripAt(k, t, startAt[k], rimAt[k], innerAt[k], top.height, p);
      drips += d.volume - notchVolume;
      puddle += d.puddleVolume;
    }
    top = candleTopFor(t, wickVolume + drips + puddle, p);
  }
  real h = top.height;
  c.height = h;
  c.poolY = h - top.hollow;
  c.volumeTarget = CANDLE_PI * R * R * p.height - p.burnRate * t;
  c.volumeDrips = drips;
  c.volumePuddle = puddle;
  CandleOutline o = candleOutlineAt(h, c.poolY, c.poolRadius, topInner, c.smoothing, p);
  c.profileCount = o.count;
  for (int i = 0; i < CANDLE_PROFILE_POINTS / 2; ++i)
    c.profile[i] = real4(o.points[2 * i].x, o.points[2 * i].y, o.points[2 * i + 1].x, o.points[2 * i + 1].y);
  c.wickBottom = c.poolY - c.poolDepth - CANDLE_WICK_ROOT_DEPTH;
  c.wickTop = c.poolY + p.wickExposed;
  c.flameY = c.wickTop + p.flameLift;
  c.dripClipY = h - real(0.0002);
  // The drips, their notches and their puddles.
  c.dripCount = started;
  c.notchCount = started;
  c.puddleCount = 0;
  c.puddleArea = real(0);
  c.dripsFrozen = 0;
  c.reach = R;
  c.low = real(0);
  for (int k = 0; k < CANDLE_MAX_DRIPS; ++k) {
    if (k >= started) break;
    CandleDrip d = candleDripAt(k, t, startAt[k], rimAt[k], innerAt[k], c.dripClipY, p);
    real angle = candleOverflowAngle(k, p);
    real3 notchCentre = real(0.5) * (R + topInner) * real3(cos(angle), real(0), sin(angle)) +
                        real3(real(0), h + CANDLE_NOTCH_RADIUS - CANDLE_NOTCH_DEPTH, real(0));
    c.notch[k] = real4(notchCentre.x, notchCentre.y, notchCentre.z, CANDLE_NOTCH_RADIUS);
    real3 lo = d.centre[0], hi = d.centre[0];
    real biggest = real(0);
    for (int i = 0; i < CANDLE_DRIP_SPHERES; ++i) {
      c.drip[CANDLE_DRIP_SPHERES * k + i] = real4(d.centre[i].x, d.centre[i].y, d.centre[i].z, d.radius[i]);
      lo = min(lo, d.centre[i]);
      hi = max(hi, d.centre[i]);
      biggest = max(biggest, d.radius[i]);
      c.reach = max(c.reach, length(real2(d.centre[i].x, d.centre[i].z)) + d.radius[i]);
      c.low = min(c.low, d.centre[i].y - d.radius[i]);
    }
    real3 boundCentre = real(0.5) * (lo + hi);
    c.dripBound[k] = real4(boundCentre.x, boundCentre.y, boundCentre.z, real(0.5) * length(hi - lo) + biggest);
    if (d.frozen) c.dripsFrozen += 1;
    if (d.puddleVolume > real(0)) {
      real rho = candlePuddleRadius(d.puddleVolume, R, p.puddleThickness);
      real along = length(real2(d.foot.x, d.foot.z));
      real3 toward = along > real(0) ? real3(d.foot.x / along, real(0), d.foot.z / along) : real3(real(1), real(0), real(0));
      real3 lobe = candlePuddleOffset(rho, R) * toward;
      c.puddle[c.puddleCount] = real4(lobe.x, lobe.y, lobe.z, rho);
      c.puddleCount += 1;
      c.puddleArea += CANDLE_PI * rho * rho - candleLensArea(rho, R, candlePuddleOffset(rho, R));
      c.reach = max(c.reach, candlePuddleOffset(rho, R) + rho);
    }
  }
  c.high = max(h, c.wickTop);
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

// A puddle lobe: a flat-bottomed puck on the table, footprint radius rho, thickness e (a disc of
// radius rho − e at y = 0 swept by a ball of radius e, cut by the table).
TALLOW_FN CandleSdf candlePuck(real3 p, real3 centre, real rho, real e) {
  real3 q = p - centre;
  real s = length(real2(q.x, q.z));
  real3 radial = s > real(0) ? real3(q.x / s, real(0), q.z / s) : real3(real(0));
  real beyond = max(s - (rho - e), real(0));
  real l = length(real2(beyond, q.y));
  CandleSdf puck = l > real(0) ? candleSdf(l - e, (beyond / l) * radial + (q.y / l) * real3(real(0), real(1), real(0)))
                               : candleSdf(-e, real3(real(0), real(1), real(0)));
  // The table's side: y ≥ 0.
  if (-p.y > puck.d) return candleSdf(-p.y, real3(real(0), real(-1), real(0)));
  return puck;
}

// Point i of the outline (radius, y), two to a four-vector.
TALLOW_FN real2 candleProfilePoint(CandleShape c, int i) {
  real4 pair = c.profile[i / 2];
  if (i % 2 == 0) return real2(pair.x, pair.y);
  return real2(pair.z, pair.w);
}

// The outline revolved: the exact distance to the polygon in the (radius, height) half-plane, its
// sign from the crossings of a ray toward +radius (the closing edge on the axis is never crossed,
// and is no surface: it is left out of the distance).
TALLOW_FN CandleSdf candleOutline(real3 p, CandleShape c) {
  real rho = length(real2(p.x, p.z));
  real3 radial = rho > real(0) ? real3(p.x / rho, real(0), p.z / rho) : real3(real(1), real(0), real(0));
  real2 q = real2(rho, p.y);
  real best = real(1e30);
  real2 nearest = q;
  real2 normal = real2(real(0), real(1));  // the nearest edge's outward normal
  bool atCorner = false;
  bool inside = false;
  for (int i = 0; i + 1 < CANDLE_PROFILE_POINTS; ++i) {
    if (i + 1 >= c.profileCount) break;
    real2 a = candleProfilePoint(c, i);
    real2 b = candleProfilePoint(c, i + 1);
    real2 e = b - a;
    real2 w = q - a;
    real ee = dot(e, e);
    real s = ee > real(0) ? clamp(dot(w, e) / ee, real(0), real(1)) : real(0);
    real2 off = w - s * e;
    real dd = dot(off, off);
    if (dd < best) {
      best = dd;
      nearest = a + s * e;
      // Counter-clockwise: the outside is to the right of each edge.
      normal = ee > real(0) ? real2(e.y, -e.x) / sqrt(ee) : normal;
      atCorner = s <= real(0) || s >= real(1);
    }
    if ((a.y > q.y) != (b.y > q.y)) {
      real x = a.x + (q.y - a.y) * (b.x - a.x) / (b.y - a.y);
      if (x > q.x) inside = !inside;
    }
  }
  real dist = sqrt(best);
  // Beside an edge the gradient is its normal on either side; nearest a corner it points from the
  // corner to p (away from the wax), unless p is too close to it for that direction to be known.
  real2 g = normal;
  if (atCorner && dist > real(1e-7)) {
    g = (q - nearest) / dist;
    if (inside) g = -g;
  }
  if (inside) dist = -dist;
  return candleSdf(dist, g.x * radial + g.y * real3(real(0), real(1), real(0)));
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

// a and b, smoothed: −smoothUnion(−a, −b).
TALLOW_FN CandleSdf candleSmoothIntersect(CandleSdf a, CandleSdf b, real k) {
  CandleSdf u = candleSmoothUnion(candleSdf(-a.d, -a.g), candleSdf(-b.d, -b.g), k);
  return candleSdf(-u.d, -u.g);
}

// --- the candle ---------------------------------------------------------------------------------

// Drip i: its four round cones, clipped below the top.
TALLOW_FN CandleSdf candleDrip(real3 p, int i, CandleShape c) {
  int s = CANDLE_DRIP_SPHERES * i;
  CandleSdf d = candleSdf(real(1e30), real3(real(0)));
  for (int j = 0; j + 1 < CANDLE_DRIP_SPHERES; ++j) {
    real4 a = c.drip[s + j];
    real4 b = c.drip[s + j + 1];
    CandleSdf next = candleRoundCone(p, real3(a.x, a.y, a.z), a.w, real3(b.x, b.y, b.z), b.w);
    if (next.d < d.d) d = next;
  }
  return candleSmoothIntersect(d, candleSdf(p.y - c.dripClipY, real3(real(0), real(1), real(0))), c.smoothing);
}

// The candle's signed distance at p (metres, negative inside) clamped to ± band, and its gradient
// (0 where clamped).
TALLOW_FN CandleSdf candleField(real3 p, CandleShape c) {
  real k = c.smoothing;
  // Early outs that return what the full evaluation returns. The smooth min lies at most k/4 below
  // the min, the smooth max at most k/4 above the max, so: (1) every part lies in the cylinder
  // (reach, low, high), so the field is at least the distance to it − k/4 and clamps to +band where
  // that is ≥ band; (2) below −band after the notches, the unions that follow keep it there.
  real slack = c.band + real(0.25) * k;
  if (candleCylinder(p, c.reach, c.low, c.high).d >= slack) return candleSdf(c.band, real3(real(0)));
  CandleSdf wax = candleOutline(p, c);
  for (int i = 0; i < CANDLE_MAX_DRIPS; ++i) {
    if (i >= c.notchCount) break;
    CandleSdf notch = candleSphere(p, real3(c.notch[i].x, c.notch[i].y, c.notch[i].z), c.notch[i].w);
    if (notch.d < slack + k) wax = candleSmoothSubtract(wax, notch, k);
  }
  // The drips, the puddle and the wick are unions: they only lower the value.
  if (wax.d <= -c.band) return candleSdf(-c.band, real3(real(0)));
  for (int i = 0; i < CANDLE_MAX_DRIPS; ++i) {
    if (i >= c.dripCount) break;
    // A drip farther than the band (and the blend) cannot change the value: skip its cones.
    real4 bound = c.dripBound[i];
    if (length(p - real3(bound.x, bound.y, bound.z)) - bound.w >= slack + k) continue;
    wax = candleSmoothUnion(wax, candleDrip(p, i, c), k);
  }
  for (int i = 0; i < CANDLE_MAX_DRIPS; ++i) {
    if (i >= c.puddleCount) break;
    real4 lobe = c.puddle[i];
    wax = candleSmoothUnion(wax, candlePuck(p, real3(lobe.x, lobe.y, lobe.z), lobe.w, c.puddleThickness), k);
  }
  CandleSdf wick = candleCylinder(p, c.wickRadius, c.wickBottom, c.wickTop);
  if (wick.d < wax.d) wax = wick;
  if (wax.d >= c.band) return candleSdf(c.band, real3(real(0)));
  if (wax.d <= -c.band) return candleSdf(-c.band, real3(real(0)));
  return wax;
}

TALLOW_FN real candleFieldValue(real3 p, CandleShape c) { return candleField(p, c).d; }
TALLOW_FN real3 candleFieldGradient(real3 p, CandleShape c) { return candleField(p, c).g; }

// Whether p lies in the liquid pool: under its free surface, over its floor (a paraboloid of the
// pool's depth on the axis meeting the surface at the pool's edge), within its radius. tol widens
// it (a surface vertex on the free surface is within tol of it).
TALLOW_FN bool candleInPool(real3 p, CandleShape c, real tol) {
  real rho = length(real2(p.x, p.z));
  if (rho > c.poolRadius || p.y > c.poolY + tol) return false;
  real u = rho / max(c.poolRadius, real(1e-9));
  return p.y >= c.poolY - c.poolDepth * (real(1) - u * u) - tol;
}
