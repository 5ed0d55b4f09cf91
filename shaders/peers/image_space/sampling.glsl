// The per-sample pieces of the image-space method (Mertens, Kautz, Bekaert, Van Reeth and Seidel
// 2003, "the image-space paper", §§5–6): the combined (importance + uniform) sample pattern with its
// balance-heuristic weights, and the map from x_o's tangent plane onto the surface seen in the
// camera image with its Jacobian. Written once and compiled as GLSL (shaders/image_space/*.frag,
// pattern.comp) and as C++ (tests/dipole_sampling_test.cpp, tests/image_space_gltest.cpp).
// Conventions: shaders/bssrdf/real.glsl; in C++ the including namespace also supplies `uint`
// (std::uint32_t), as for shaders/sss/estimator.glsl. Documentation: docs/image-space.md.
#ifdef TALLOW_GLSL
#include "maps/estimator.glsl"
#include "maps/dipole_sampling.glsl"
#endif

// --- Combined sampling (§6.1) ------------------------------------------------------------------
// Sample j (0 … n − 1) of a set: the first nUniform are uniform on the disc, the others importance
// samples of R_d of the colour bands in turn (band (j − nUniform) mod 3, each with its own σ_tr):
// strategy −1 is uniform, 0 … 2 the bands.
TALLOW_FN int isStrategy(int j, int nUniform) { return j < nUniform ? -1 : (j - nUniform) % 3; }
// The index of sample j among the samples of its strategy.
TALLOW_FN int isStrategyIndex(int j, int nUniform) { return j < nUniform ? j : (j - nUniform) / 3; }
// How many of the n samples use `strategy`: nUniform, or the k < n − nUniform with k mod 3 = band.
TALLOW_FN int isStrategyCount(int strategy, int n, int nUniform) {
  if (strategy < 0) return nUniform;
  return max(n - nUniform - strategy + 2, 0) / 3;
}

// The k-th of the n points of one strategy: a Hammersley set, (k + ρ₁)/n in ξ₁ and the base-2
// radical inverse Φ₂(k) + ρ₂ (mod 1) in ξ₂, rotated by (ρ₁, ρ₂) (Cranley–Patterson) per set,
// strategy and frame. Every set is stratified on its own in r (through ξ₁, which the CDF maps
// monotonically) and in angle, and the frames' rotations make the accumulation unbiased.
TALLOW_FN real2 isStratifiedPoint(int k, int n, real rot1, real rot2) {
  real u = (real(k) + rot1) / real(max(n, 1));
  real v = sssRadicalInverse(uint(k), 2u) + rot2;
  return real2(min(u, DIPOLE_XI_MAX), v - floor(v));
}

// One entry of the sample pattern: where a sample lies in x_o's tangent frame and what it weighs.
struct IsPatternEntry {
  real2 offset;    // (r cos φ, r sin φ) [mm] along the tangent frame (t1, t2) of x_o
  real weight;     // 1/Σ_s n_s p_s(r) [mm²]: the balance heuristic (Veach and Guibas 1995) weight of
                   // the sample over its density, so that B = Σ_j f(x_j) · weight_j
  real3 coverage;  // p_b(r) · weight per band: summed over the samples that find surface, an
                   // estimate of the share of band b's importance density R_d,b/∫R_d,b on that surface
};

// The disc's radius [mm]: `radiusMfp` times the longest mean free path 1/σ_tr of the three bands,
// one disc for all bands so that the strategies combine.
TALLOW_FN real isDiscRadius(BssrdfCoefficients k0, BssrdfCoefficients k1, BssrdfCoefficients k2, real radiusMfp) {
  return radiusMfp * max(dipoleMeanFreePath(k0), max(dipoleMeanFreePath(k1), dipoleMeanFreePath(k2)));
}

// Sample j of n (nUniform of them uniform) of sample set `set` at frame `frame`, for a material
// whose bands have coefficients k0, k1, k2 (standard dipole), on the disc of `radiusMfp` mean free
// paths. The density of the combination is D(r) = Σ_b n_b R_d,b(r)/∫_disc R_d,b + n_u/(πR²); the
// sample's weight is 1/D (the balance heuristic), so f/D summed over all n samples estimates ∫ f dA.
TALLOW_FN IsPatternEntry isPatternEntry(BssrdfCoefficients k0, BssrdfCoefficients k1, BssrdfCoefficients k2,
                                        real radiusMfp, int j, int n, int nUniform, uint set, uint frame) {
  real radius = isDiscRadius(k0, k1, k2, radiusMfp);
  DipoleSampler s0 = dipoleSampler(k0, radius);
  DipoleSampler s1 = dipoleSampler(k1, radius);
  DipoleSampler s2 = dipoleSampler(k2, radius);
  int strategy = isStrategy(j, nUniform);
  // ρ from the radiosity maps' counter hash: stream (set, 0, strategy + 1, frame).
  real rot1 = sssRandom(set, 0u, uint(strategy + 1), frame, 0u, 0u, 0u);
  real rot2 = sssRandom(set, 0u, uint(strategy + 1), frame, 0u, 0u, 1u);
  real2 xi = isStratifiedPoint(isStrategyIndex(j, nUniform), isStrategyCount(strategy, n, nUniform), rot1, rot2);
  real r = dipoleUniformRadius(radius, xi.x);
  if (strategy == 0) r = dipoleSampleRadius(s0, xi.x).r;
  if (strategy == 1) r = dipoleSampleRadius(s1, xi.x).r;
  if (strategy == 2) r = dipoleSampleRadius(s2, xi.x).r;
  real phi = DIPOLE_TWO_PI * xi.y;
  real3 p = real3(dipoleAreaPdf(s0, r), dipoleAreaPdf(s1, r), dipoleAreaPdf(s2, r));
  real d = real(isStrategyCount(0, n, nUniform)) * p.x + real(isStrategyCount(1, n, nUniform)) * p.y +
           real(isStrategyCount(2, n, nUniform)) * p.z + real(nUniform) * dipoleUniformPdf(radius, r);
  IsPatternEntry e;
  e.offset = r * real2(cos(phi), sin(phi));
  e.weight = d > real(0) ? real(1) / d : real(0);
  e.coverage = p * e.weight;
  return e;
}

// --- From the tangent plane to the surface in the image (§5, Eq. 8) ---------------------------
// Below this cosine between the camera ray and the surface found in the image, the Jacobian is
// bounded (a surface seen edge-on would give dA/dA' → ∞ from a pixel that hardly samples it).
const real IS_MIN_SURFACE_COS = 0.05;

// The camera ray's direction at a world point: from the eye (perspective) or the view direction
// (orthographic).
TALLOW_FN real3 isViewRay(real3 point, real3 eye, real3 forward, int orthographic) {
  if (orthographic != 0) return forward;
  return normalize(point - eye);
}

// dA_p/dA_p' of the projection through the camera of the tangent-plane point p' (plane normal n_o)
// onto the surface point p (normal n_p) on the same camera ray: both subtend the same solid angle
// from the eye e, dA_p cos θ/d² = dA_p' cos θ'/d'² (§5), so dA_p/dA_p' = (cos θ'/cos θ)(d²/d'²),
// with θ, θ' between the ray and n_p, n_o and d = |e − p|, d' = |e − p'|; an orthographic camera
// keeps cross-sections, dA_p cos θ = dA_p' cos θ'. (The paper prints the reciprocal in Eq. 9 and
// leaves the factor out of its GPU version; tests/dipole_sampling_test.cpp measures it on a sphere.)
TALLOW_FN real isAreaRatio(real3 pPrime, real3 no, real3 p, real3 np, real3 eye, real3 forward, int orthographic) {
  real3 ray = isViewRay(pPrime, eye, forward, orthographic);
  real ratio = abs(dot(ray, no)) / max(abs(dot(ray, np)), IS_MIN_SURFACE_COS);
  if (orthographic == 0) {
    real3 a = p - eye;
    real3 b = pPrime - eye;
    ratio = ratio * dot(a, a) / max(dot(b, b), real(1e-30));
  }
  return ratio;
}
