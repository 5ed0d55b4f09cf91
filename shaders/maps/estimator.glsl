// The Monte Carlo estimator of scattered radiosity of the radiosity-maps paper (Dal Corso, Frisvad,
// Kjeldsen and Bærentzen, §3–3.3, Eqs. 8–14): the per-sample pieces, written once and compiled as
// GLSL (the scattered-radiosity map pass) and as C++ in float and double (sss/maps/radiosity_estimator.cpp,
// the tests). Conventions: shaders/bssrdf/real.glsl; in C++ the including namespace also supplies
// `uint` (std::uint32_t), whose *, +, ^, >> wrap modulo 2³² exactly like GLSL's uint.
// Documentation: docs/radiosity-maps.md, "The estimator".
//
// Units: lengths in mm, coefficients in mm⁻¹ (the BSSRDF convention); the caller converts scene
// units. Directions are unit vectors; `wl` points from x_i toward the light (= −ω_ℓ of the paper).
#ifdef TALLOW_GLSL
#include "bssrdf/bssrdf.glsl"
#endif

const real SSS_TWO_PI = 6.28318530717958647692;
// 2⁻²⁴: the 24 top bits of a 32-bit hash times this is a real in [0, 1) that float represents
// exactly, so the float and the double instantiations (and the GPU) draw identical ξ.
const real SSS_INV_2_POW_24 = 5.9604644775390625e-8;

// --- Counter-based random numbers -----------------------------------------------------------
// The PCG hash: one step of the 32-bit linear congruential generator of PCG (multiplier
// 747796405, increment 2891336453) followed by PCG's RXS-M-XS output permutation (a random
// xorshift by 4 + the top 4 bits, a multiply by 277803737, an xorshift by 22), used as a stateless
// hash of the counter. O'Neill, "PCG: A family of simple fast space-efficient statistically good
// algorithms for random number generation", HMC-CS-2014-0905 (2014), §6.3; recommended as a GPU
// hash by Jarzynski and Olano, "Hash Functions for GPU Rendering", JCGT 9(3), 2020 (§2, "pcg").
TALLOW_FN uint sssPcgHash(uint v) {
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

// The hash of a tuple by nesting, h(a + h(b + h(c …))) (Jarzynski and Olano 2020, §3, the
// construction of multidimensional inputs from a 1D hash). Each coordinate enters through its own
// level, so two tuples that differ in any coordinate give unrelated values.
//   x, y: texel of the scattered-radiosity map; map: its index k; frame: the accumulated-frame
//   counter F; band: colour band c (§3.1: each band its own sample positions), or SSS_SHARED_BAND
//   for the pattern the three bands share (sssDrawSharedSample); sampleIndex: j;
//   dim: which number of the sample (0: ξ1 for r, 1: ξ2 for α, 2: a point light's pick of density).
TALLOW_FN uint sssRandomBits(uint x, uint y, uint map, uint frame, uint band, uint sampleIndex, uint dim) {
  uint h = sssPcgHash(dim);
  h = sssPcgHash(sampleIndex + h);
  h = sssPcgHash(band + h);
  h = sssPcgHash(frame + h);
  h = sssPcgHash(map + h);
  h = sssPcgHash(y + h);
  return sssPcgHash(x + h);
}

// ξ ∈ [0, 1): the top 24 bits of the hash × 2⁻²⁴ (exact in float and double alike).
TALLOW_FN real sssRandom(uint x, uint y, uint map, uint frame, uint band, uint sampleIndex, uint dim) {
  return real(sssRandomBits(x, y, map, frame, band, sampleIndex, dim) >> 8u) * SSS_INV_2_POW_24;
}

// --- Exponential sampling of the distance (Eqs. 10–12) --------------------------------------
// σ_tr = √(3σ_a(σ_a + (1 − g)σ_s)) (Eq. 10) is k.sigmaTr. Without absorption (σ_a = 0, e.g.
// Spectralon) it is 0 and Eq. 12 would put every sample at infinity; the dipoles then fall off as a
// power of r, not exponentially. The sampling rate is therefore bounded below by
// SSS_MIN_SIGMA_TR_RATIO σ_t' (σ_t' > 0 always: σ_a + σ_s > 0, |g| < 1) and by SSS_MIN_SIGMA_TR. Any
// positive rate keeps the estimator unbiased (the pdf is positive on [0, ∞)); the bound only
// changes which r are drawn. It is reached only where σ_a/σ_t' < 3.3·10⁻⁷, far below every measured
// medium with σ_a > 0 in materials.csv (the nearest, Cream's red band, has σ_tr/σ_t' = 0.009).
const real SSS_MIN_SIGMA_TR_RATIO = 1e-3;
const real SSS_MIN_SIGMA_TR = 1e-6;  // mm⁻¹

// The rate of the exponential distance distribution for one band [mm⁻¹], > 0.
TALLOW_FN real sssSamplingSigmaTr(BssrdfCoefficients k) {
  return max(k.sigmaTr, max(SSS_MIN_SIGMA_TR_RATIO * k.sigmaTp, SSS_MIN_SIGMA_TR));
}

// p(r, α) = σ_tr e^{−σ_tr r}/(2π) (Eq. 11) [mm⁻² per radian … i.e. per dr dα].
TALLOW_FN real sssRadialPdf(real r, real sigmaTr) {
  return sigmaTr * exp(-sigmaTr * r) / SSS_TWO_PI;
}

// One (r, α) pair of Eq. 12 and the Monte Carlo weight r/p(r, α) of Eq. 9.
// r = −log(1 − ξ1)/σ_tr: the paper's −log ξ1 with ξ1 ∈ (0, 1] mirrored onto our ξ1 ∈ [0, 1), so r is
// finite (r ≤ 24 log 2/σ_tr ≈ 16.6/σ_tr). The weight uses e^{−σ_tr r} = 1 − ξ1 exactly:
// r/p = 2π r/(σ_tr (1 − ξ1)), which never underflows to a division by 0.
struct SssRadialSample {
  real r;       // mm
  real alpha;   // radians, [0, 2π)
  real weight;  // r/p(r, α) [mm²]
};

TALLOW_FN SssRadialSample sssSampleRadial(real xi1, real xi2, real sigmaTr) {
  real survival = real(1) - xi1;  // in [2⁻²⁴, 1]
  SssRadialSample s;
  s.r = -log(survival) / sigmaTr;
  s.alpha = SSS_TWO_PI * xi2;
  s.weight = SSS_TWO_PI * s.r / (sigmaTr * survival);
  return s;
}

// The planar sample point x_j = x_o + r (cos α t1 + sin α t2) in the tangent plane spanned by the
// orthonormal t1, t2 (§3: the light's view plane for a directional light; x_o's tangent plane for
// the cube-map G-buffer of a point light, §3.3).
TALLOW_FN real3 sssPlanarSamplePoint(real3 xo, real3 t1, real3 t2, real r, real alpha) {
  return xo + r * (cos(alpha) * t1 + sin(alpha) * t2);
}

// Everything one sample needs before the G-buffer look-up: the random pair of stream (x, y, map,
// frame, band, sample), the distance and angle, the weight and the point x_j.
struct SssSample {
  real3 xj;
  real r;
  real alpha;
  real weight;
};


// --- Point lights: a second distance density and their mixture (issue 17) ---------------------
// Eq. 12's exponential puts almost no samples where a point light inside the object lights x_o from
// afar (the candle's lower wall, lit by the cup's inside 3–5 cm away: σ_tr r > 7 holds 95% of the
// second moment and 0.09% of the samples), and ξ's 24 bits cut it at r = 16.6/σ_tr. The second
// density is the stereographic image of uniform directions about the light: x_j on x_o's tangent
// plane whose inverse stereographic projection from the antipode (Eqs. 13–14) is uniform on the
// sphere of radius R = |x_ℓ − x_o| about x_ℓ. Per unit area of the plane (the plane normal to
// x_ℓ − x_o, where the conformal factor is exact)
//   p₂(r) = (1 + r²/4R²)⁻² / (4πR²),   ∫ p₂ dA = ∫₀^∞ (1 + u)⁻² du = 1   (u = r²/4R²),
// with the cumulative F(r) = u/(1 + u), so r = 2R √(ξ/(1 − ξ)) draws it. Per (r, α), as Eq. 11 is
// written: p₂(r, α) = r p₂(r). Each sample picks the stereographic density with probability `share`,
// otherwise Eq. 12, and is weighted by the mixture (the balance heuristic of Veach and Guibas 1995,
// one-sample MIS): weight = r/((1 − share) p(r, α) + share p₂(r, α)) (sssDrawSharedSample below). The
// mixture is positive at every r > 0 when share > 0, so no distance is cut off: the bias of Eq. 12's
// truncation goes.

// p₂(r, α) = r (1 + r²/4R²)⁻²/(4πR²) [per mm per radian], R > 0.
TALLOW_FN real sssStereoRadialPdf(real r, real radius) {
  real q = real(1) + r * r / (real(4) * radius * radius);
  return r / (real(2) * SSS_TWO_PI * radius * radius * q * q);
}

// r of p₂ from ξ ∈ [0, 1): 2R √(ξ/(1 − ξ)) (finite: 1 − ξ ≥ 2⁻²⁴).
TALLOW_FN real sssSampleStereoRadius(real xi, real radius) {
  return real(2) * radius * sqrt(xi / (real(1) - xi));
}

// --- One sample pattern for the three colour bands (issue 17) -------------------------------
// §3.1 draws each band's samples from its own σ_tr, so a rare sample that reaches a bright x_i lands
// in one band only: coloured speckles, and three G-buffer look-ups, x_i and area ratios per sample.
// Instead each sample's r is drawn once from the mixture of the three bands' Eq. 12 densities (and,
// for a point light, p₂ with probability `share`),
//   p_mix(r, α) = (1 − share)·(p_r + p_g + p_b)/3 + share·p₂,
// and every band is weighted by r/p_mix (the balance heuristic over the four techniques, Veach and
// Guibas 1995): unbiased for each band since p_mix > 0 wherever that band's Eq. 12 is, and at most
// 3/(1 − share) times that band's own weight r/p_c. The bands then share x_j, the look-up, x_i, n_i
// and the area ratio, and their errors are correlated: grey noise instead of colour noise.
// The random stream's band coordinate is SSS_SHARED_BAND for these samples.
const uint SSS_SHARED_BAND = 3u;

// p_mix(r, α) [per mm per radian] for the rates σ_tr of the three bands (all > 0).
TALLOW_FN real sssBandMixturePdf(real r, real3 sigmaTr, real radius, real share) {
  real p = (real(1) - share) *
           ((sssRadialPdf(r, sigmaTr.x) + sssRadialPdf(r, sigmaTr.y)) + sssRadialPdf(r, sigmaTr.z)) / real(3);
  if (share > real(0)) p = p + share * sssStereoRadialPdf(r, radius);
  return p;
}

// Sample j of N = sampleCount of the shared pattern: the technique picked by fract(ξ₀ + j/N), with
// one ξ₀ per texel and frame (dimension 2 of sample 0): p₂ below `share` (point lights with
// R = radius > 0 only; pass share = 0 for directional lights), else the Eq. 12 of band
// ⌊3 (pick − share)/(1 − share)⌋; r and α from dimensions 0 and 1; weight r/p_mix. Each pick is
// uniform on [0, 1), so every sample is a one-sample MIS estimate, and together the N picks are
// stratified: a technique of probability q gets ⌊N·q⌋ or ⌈N·q⌉ of them, no variance from how many.
TALLOW_FN SssSample sssDrawSharedSample(real3 xo, real3 t1, real3 t2, real3 sigmaTr, real radius, real share, uint x,
                                        uint y, uint map, uint frame, uint sampleIndex, uint sampleCount) {
  real sh = (share > real(0) && radius > real(0)) ? share : real(0);
  real xi1 = sssRandom(x, y, map, frame, SSS_SHARED_BAND, sampleIndex, 0u);
  real xi2 = sssRandom(x, y, map, frame, SSS_SHARED_BAND, sampleIndex, 1u);
  real pick = fract(sssRandom(x, y, map, frame, SSS_SHARED_BAND, 0u, 2u) + real(sampleIndex) / real(max(sampleCount, 1u)));
  SssSample s;
  if (pick < sh) {
    s.r = sssSampleStereoRadius(xi1, radius);
  } else {
    real band = real(3) * (pick - sh) / (real(1) - sh);  // in [0, 3)
    real rate = band < real(1) ? sigmaTr.x : (band < real(2) ? sigmaTr.y : sigmaTr.z);
    s.r = -log(real(1) - xi1) / rate;
  }
  s.alpha = SSS_TWO_PI * xi2;
  real p = sssBandMixturePdf(s.r, sigmaTr, radius, sh);
  s.weight = p > real(0) ? s.r / p : real(0);
  s.xj = sssPlanarSamplePoint(xo, t1, t2, s.r, s.alpha);
  return s;
}

// --- Directional lights on thick, backlit objects (issue 17) -------------------------------
// Where x_o lies on the far side of a thick object, the light enters a depth h ahead of it along the
// light (the light G-buffer at x_o's own place), and the integrand over the view plane falls as
// exp(−σ_tr √(r² + h²)): for h σ_tr ≫ 1 a Gaussian of width √(h/σ_tr), wider than Eq. 12's 1/σ_tr,
// so Eq. 12's samples rarely reach where it lies (heavy-tailed weights: speckles, and a frame's
// mean short of the truth). The gather then mixes in p₂ as for a point light, with
// 2R = √(h/σ_tr) of the band that reaches furthest (smallest σ_tr); R = 0 (Eq. 12 alone) where
// h σ_tr ≤ 1, a front-lit or thin x_o.
TALLOW_FN real sssBacklitRadius(real depth, real sigmaTrMin) {
  if (depth * sigmaTrMin <= real(1)) return real(0);
  return real(0.5) * sqrt(depth / sigmaTrMin);
}

// --- Point lights: the cube-map look-up direction (§3.3) ------------------------------------
// Planar sampling looks the cube-map G-buffer up along x_j − x_ℓ.
TALLOW_FN real3 sssPlanarLookupDirection(real3 xj, real3 xl) { return xj - xl; }

// Stereographic correction (Eqs. 13–14): with a = x_ℓ − x_o and
//   ℓ = ((x_j − x_ℓ) − a)/‖(x_j − x_ℓ) − a‖                      (Eq. 14),
//   x_stereo − x_ℓ = a − 2 (a·ℓ) ℓ                                  (Eq. 13).
// Since (x_j − x_ℓ) − a = x_j − x_a with x_a = x_ℓ + a the antipode of x_o on the sphere of radius
// ‖a‖ around x_ℓ, this reflects a about the plane normal to the line x_a → x_j: x_stereo is where
// that line meets the sphere again, the inverse stereographic projection of x_j from x_a. Hence
// ‖x_stereo − x_ℓ‖ = ‖a‖; r → 0 (x_j = x_o) gives ℓ = −a/‖a‖ and x_stereo − x_ℓ = −a = x_o − x_ℓ, the
// planar direction; r → ∞ tends to a, the antipode, so the whole cube map is reachable.
// Degenerate inputs: x_o = x_ℓ (a = 0) returns the planar direction x_j − x_ℓ; x_j = x_a (ℓ
// undefined) returns a, the limit along any line.
TALLOW_FN real3 sssStereographicLookupDirection(real3 xo, real3 xj, real3 xl) {
  real3 a = xl - xo;
  if (dot(a, a) <= real(0)) return xj - xl;
  real3 d = (xj - xl) - a;
  real len = length(d);
  if (!(len > real(0))) return a;
  real3 l = d / len;
  return a - real(2) * dot(a, l) * l;
}

// --- The sampling plane's area against the surface's (point lights) ---------------------------
// The samples x_j have the density of Eq. 12 on x_o's tangent plane; the look-up moves each to the
// surface point x_i, so Eq. 7 over the surface needs dA_i/dA_j in every term (the paper's Eq. 9
// leaves it out). Both look-ups are projections through a point, so areas follow solid angles:
// dω = dA cos β / d² at each end, with β between the ray and the area's normal.
//   Planar (x_i on the ray x_ℓ → x_j):  dA_i/dA_j = (cos β_j / d_j²) · (d_i² / cos θ_i).
//   Stereographic (Eqs. 13–14): x_j → x_s on the sphere of radius R = |x_ℓ − x_o| about x_ℓ along the
//   line from the antipode x_a = 2x_ℓ − x_o; a chord from x_a meets the sphere at the same angle β
//   at both ends and is 2R cos β long, so dA_s/dA_j = 4R² cos β cos β_j / |x_j − x_a|² (= 1 at
//   x_j = x_o; (1 + r²/4R²)⁻² when the tangent plane is normal to x_ℓ − x_o, the conformal factor);
//   then x_s → x_i through x_ℓ: dA_i/dA_s = d_i² / (R² cos θ_i).
// cos θ_i = |n_i · (x_i − x_ℓ)/d_i| is the cos θ_ℓ of the term, so the product stays finite at
// grazing light (bounded below by 10⁻³ as for directional lights).
TALLOW_FN real sssSurfaceOverSolidAngle(real3 xi, real3 ni, real3 xl) {
  real3 di = xi - xl;
  real d2 = dot(di, di);
  if (!(d2 > real(0))) return real(0);
  return d2 / max(abs(dot(di, ni)) / sqrt(d2), real(1e-3));  // d_i² / cos θ_i
}
TALLOW_FN real sssPlanarAreaRatio(real3 no, real3 xj, real3 xl, real3 xi, real3 ni) {
  real3 dj = xj - xl;
  real dj2 = dot(dj, dj);
  if (!(dj2 > real(0))) return real(0);
  real cosJ = abs(dot(dj, no)) / sqrt(dj2);
  return cosJ / dj2 * sssSurfaceOverSolidAngle(xi, ni, xl);
}
TALLOW_FN real sssStereographicAreaRatio(real3 xo, real3 no, real3 xj, real3 xl, real3 xi, real3 ni) {
  real3 a = xl - xo;
  real r2 = dot(a, a);
  if (!(r2 > real(0))) return sssPlanarAreaRatio(no, xj, xl, xi, ni);
  real3 v = xj - (xl + a);
  real l2 = dot(v, v);
  if (!(l2 > real(0))) return real(0);
  real l = sqrt(l2);
  real cosB = abs(dot(v, a)) / (l * sqrt(r2));
  real cosJ = abs(dot(v, no)) / l;
  real sphereOverPlane = real(4) * r2 * cosB * cosJ / l2;  // dA_s/dA_j
  return sphereOverPlane / r2 * sssSurfaceOverSolidAngle(xi, ni, xl);
}

// --- x_i from the light G-buffer texel (§3.1) -----------------------------------------------
// The sample looks the G-buffer up along the line x(t) = origin + t d (d unit: toward the light from
// x_j for a directional light, from the light through x_j for a point light); the texel holds the
// surface point p seen at its centre and the normal n there. Keeping x_j's exact place across the
// line and taking the texel's depth along it (onPlane = 0) puts x_i off a surface that is tilted
// against the G-buffer's view plane by up to half a texel × tan θ_ℓ along d: r = |x_o − x_i| then
// never comes closer than that offset, which cuts off the peak of S_d at r → 0 and loses light at
// grazing incidence (on the slab lit at 60°, 7–11% with 512² texels; the loss falls as the texel's
// square). onPlane = 1 intersects the line with the texel's tangent plane instead — exact on planes,
// off by the surface's curvature × the squared offset elsewhere — unless the line runs within
// SSS_TEXEL_PLANE_MIN_COS of the plane (grazing), where the extrapolation is not trusted.
const real SSS_TEXEL_PLANE_MIN_COS = 0.2;
TALLOW_FN real3 sssPointOnTexel(real3 origin, real3 d, real3 p, real3 n, int onPlane) {
  real along = dot(p - origin, d);
  real cosine = dot(d, n);
  if (onPlane != 0 && abs(cosine) >= SSS_TEXEL_PLANE_MIN_COS) along = dot(p - origin, n) / cosine;
  return origin + along * d;
}

// --- The term of Eq. 9 ------------------------------------------------------------------------
// S_d(x_i, −ω_ℓ; x_o) F_t(−ω_ℓ) cos θ_ℓ · r/p(r, α) for one band, with
//   S_d from bssrdfEvaluate (raw model value, clamped ≥ 0 by bssrdfClamped; no Fresnel inside),
//   F_t = fresnelTransmittance(cos θ_ℓ, η) at x_i,
//   cos θ_ℓ = n_i·w_l, w_l the unit vector from x_i toward the light;
// 0 where cos θ_ℓ ≤ 0 (x_i faces away from the light: the G-buffer saw its back, or a grazing hit).
// `weight` is SssSample.weight. Photon beam diffusion runs with its default quadrature.
TALLOW_FN real sssRadiosityTerm(int model, real3 xi, real3 ni, real3 wl, real3 xo, real3 no, BssrdfCoefficients k,
                                real weight) {
  real cosL = dot(ni, wl);
  if (!(cosL > real(0))) return real(0);
  cosL = min(cosL, real(1));
  BssrdfEval e = bssrdfEvaluate(model, xi, ni, wl, xo, no, k, PBD_DEFAULT_PANELS_PER_EFOLD);
  real sd = bssrdfClamped(e.sd);
  if (!(sd > real(0))) return real(0);
  return sd * fresnelTransmittance(cosL, k.eta) * cosL * weight;
}

// B_N = (π L_ℓ/N) Σ_j term_j (Eq. 9). In the paper's Eq. 6, L_i = L_ℓ V δ(ω_i + ω_ℓ) with a unit
// delta, so a surface facing the light receives ∫ L_i cos θ dω = L_ℓ: L_ℓ is numerically the
// irradiance E [W/m²] of the directional light on a surface normal to it, and B_N is in W/m².
TALLOW_FN real sssRadiosityFromSum(real sum, real lightRadiance, int sampleCount) {
  return BSSRDF_PI * lightRadiance * sum / real(max(sampleCount, 1));
}

// --- Directions of the K map cameras (§3.2) ----------------------------------------------------
// Radical inverse of i in `base` (Halton, "Algorithm 247: Radical-inverse quasi-random point
// sequence", CACM 7(12), 1964): the base-b digits of i mirrored about the radix point.
TALLOW_FN real sssRadicalInverse(uint i, uint base) {
  real inverseBase = real(1) / real(base);
  real f = inverseBase;
  real result = real(0);
  uint n = i;
  while (n > 0u) {
    result = result + f * real(n % base);
    n = n / base;
    f = f * inverseBase;
  }
  return result;
}

// The k-th (k = 0, 1, …) of the camera directions: (u, v) = (Φ₂(k + 1), Φ₃(k + 1)) mapped to the unit
// sphere by the area-preserving z = 1 − 2u, φ = 2πv (uniform in area: dA = dz dφ).
TALLOW_FN real3 sssHaltonDirection(uint k) {
  real u = sssRadicalInverse(k + 1u, 2u);
  real v = sssRadicalInverse(k + 1u, 3u);
  real z = real(1) - real(2) * u;
  real rho = sqrt(max(real(1) - z * z, real(0)));
  real phi = SSS_TWO_PI * v;
  return real3(rho * cos(phi), rho * sin(phi), z);
}
