// Exact importance sampling of the standard dipole's diffuse reflectance R_d(r) on a plane
// (Mertens, Kautz, Bekaert, Van Reeth and Seidel 2003, "Efficient rendering of local subsurface
// scattering", §4; "the image-space paper" below), written once and compiled as GLSL (the sample
// pattern of the image-space method, shaders/peers/image_space/pattern.comp) and as C++ in float and
// double (tests/dipole_sampling_test.cpp). Conventions: shaders/bssrdf/real.glsl. Units: mm, mm⁻¹.
// Documentation: docs/image-space.md, "The sampler".
//
// R_d(r) = α'/(4π) [R_r(r) + R_v(r)],  R_s(r) = z_s (1 + σ_tr d_s) e^{−σ_tr d_s}/d_s³,  d_s = √(r² + z_s²)
// (Jensen et al. 2001, Eq. 5; shaders/bssrdf/standard_dipole.glsl evaluates it). Each term integrates
// in closed form (the paper's Eqs. 6–7):
//   ∫₀^r R_s(r') r' dr' = e^{−σ_tr z_s} F_s(r),   F_s(r) = 1 − (z_s/d_s) e^{−σ_tr (d_s − z_s)},
// so ∫ R_d dA over the disc of radius R is (α'/2) Σ_s e^{−σ_tr z_s} F_s(R). A sample picks the real or
// the virtual source with probability proportional to its term's integral over the disc, then
// inverts that term's radial CDF F_s(r)/F_s(R) = ξ by Newton's method (the paper's equation
// σ_tr z (u − 1) + log u + log(1 − ξ) = 0 in u = d/z, here with the disc's share F_s(R) in place of 1:
// the paper samples the whole plane, we sample the disc that bounds the integration, A' of its §5).
#ifdef TALLOW_GLSL
#include "bssrdf/standard_dipole.glsl"
#endif

const real DIPOLE_TWO_PI = 6.28318530717958647692;
// Largest ξ the samplers use, 1 − 2⁻²⁴ (exact in float): keeps log(1 − ξ) finite.
const real DIPOLE_XI_MAX = 0.999999940395355224609375;
// Below this |x| the series of log1p (13 terms) and expm1 (9 terms) replace log(1 + x) and
// exp(x) − 1, which lose digits there in float; the series are exact to double rounding there
// (remainders 0.05¹³/14 and 0.05⁹/9! relative), the direct forms lose at most 2⁻²⁴/0.05 ≈ 1.2·10⁻⁶
// relative above it in float, nothing in double.
const real DIPOLE_SERIES_LIMIT = 0.05;
// Newton's method stops once a step is below this share of the unknown (quadratic convergence: the
// error after that step is of the order of its square), or at the cap (tests: never reached).
const real DIPOLE_NEWTON_TOLERANCE = 1e-7;
const int DIPOLE_NEWTON_MAX_ITERATIONS = 40;
// The radius of the integration disc is given in mean free paths 1/σ_tr; without absorption σ_tr is
// 0 and R_d falls off as a power of r, so the rate is bounded below as the radiosity-maps sampler
// does (shaders/maps/estimator.glsl, SSS_MIN_SIGMA_TR_RATIO): by 10⁻³ σ_t' and 10⁻⁶ mm⁻¹.
const real DIPOLE_MIN_SIGMA_TR_RATIO = 1e-3;
const real DIPOLE_MIN_SIGMA_TR = 1e-6;

// log(1 + x), x > −1, accurate near 0: Σ_{i=1}^{13} (−1)^{i+1} x^i/i there.
TALLOW_FN real dipoleLog1p(real x) {
  if (abs(x) >= DIPOLE_SERIES_LIMIT) return log(real(1) + x);
  real sum = real(0);
  for (int i = 13; i >= 1; --i) sum = real(1) / real(i) - x * sum;
  return x * sum;
}

// exp(x) − 1, accurate near 0: x (1 + x/2 (1 + x/3 (… (1 + x/9)))) there.
TALLOW_FN real dipoleExpm1(real x) {
  if (abs(x) >= DIPOLE_SERIES_LIMIT) return exp(x) - real(1);
  real sum = real(1);
  for (int i = 9; i >= 2; --i) sum = real(1) + x / real(i) * sum;
  return x * sum;
}

// The length 1/σ_tr in which `radius` of the image-space method is counted [mm], with σ_tr
// bounded below as above.
TALLOW_FN real dipoleMeanFreePath(BssrdfCoefficients k) {
  return real(1) / max(k.sigmaTr, max(DIPOLE_MIN_SIGMA_TR_RATIO * k.sigmaTp, DIPOLE_MIN_SIGMA_TR));
}

// F_s(r): the share of one source term's integral over the whole plane that lies within radius r,
// 1 − (z/d) e^{−σ_tr (d − z)} = −expm1(−σ_tr (d − z) − log1p((d − z)/z)), with d − z = r²/(d + z)
// (no cancellation for r ≪ z). z > 0 (the source's depth or height), σ_tr ≥ 0, r ≥ 0.
TALLOW_FN real dipoleTermShare(real z, real sigmaTr, real r) {
  real d = sqrt(r * r + z * z);
  real dz = r * r / (d + z);
  return -dipoleExpm1(-(sigmaTr * dz + dipoleLog1p(dz / z)));
}

struct DipoleInversion {
  real r;          // mm
  int iterations;  // Newton steps taken
};

// The radius r at which F_s(r) = share (0 ≤ share < 1): with u = d/z = 1 + w and a = σ_tr z,
// F_s = 1 − e^{−a w}/(1 + w), so a w + log1p(w) = c with c = −log1p(−share) (the paper's equation).
// Newton's method runs on h(v) = a·expm1(v) + v − c in v = log1p(w): h is increasing and convex, so
// from a start right of the root every step stays right of it and the iterates fall monotonically
// onto it (no overshoot, no bracketing needed). The start min(c, log1p(c/a)) is right of the root
// (h(c) = a·expm1(c) ≥ 0 and h(log1p(c/a)) = log1p(c/a) ≥ 0) and exact in both limits (a → 0:
// v = c; a → ∞: v = c/a). Then r = z √(w (w + 2)) = √(d² − z²).
TALLOW_FN DipoleInversion dipoleInvertTerm(real z, real sigmaTr, real share) {
  real a = sigmaTr * z;
  real c = -dipoleLog1p(-min(max(share, real(0)), DIPOLE_XI_MAX));
  real v = c;
  if (c < a * real(1e6)) v = min(c, dipoleLog1p(c / a));  // else a ≪ c: c/a may overflow; c is right of the root too
  DipoleInversion result;
  result.iterations = 0;
  for (int i = 0; i < DIPOLE_NEWTON_MAX_ITERATIONS; ++i) {
    real h = a * dipoleExpm1(v) + v - c;
    real step = h / (a * exp(v) + real(1));
    if (!(step > real(0))) break;  // on the root, or left of it by rounding
    v = v - step;
    result.iterations = i + 1;
    if (step <= DIPOLE_NEWTON_TOLERANCE * v) break;
  }
  real w = dipoleExpm1(max(v, real(0)));
  result.r = z * sqrt(w * (w + real(2)));
  return result;
}

// Everything the sampler of one colour band needs, for the disc of radius R around x_o.
struct DipoleSampler {
  BssrdfCoefficients k;
  real radius;        // R [mm]
  real shareReal;     // F_r(R)
  real shareVirtual;  // F_v(R)
  real probReal;      // probability of the real source: its term's integral over the disc / both
  real total;         // ∫_disc R_d dA = (α'/2)(e^{−σ_tr z_r} F_r(R) + e^{−σ_tr z_v} F_v(R))
};

TALLOW_FN DipoleSampler dipoleSampler(BssrdfCoefficients k, real radius) {
  DipoleSampler s;
  s.k = k;
  s.radius = radius;
  s.shareReal = dipoleTermShare(k.zr, k.sigmaTr, radius);
  s.shareVirtual = dipoleTermShare(k.zv, k.sigmaTr, radius);
  real wr = exp(-k.sigmaTr * k.zr) * s.shareReal;  // the paper's Eq. 7 on the disc
  real wv = exp(-k.sigmaTr * k.zv) * s.shareVirtual;
  s.probReal = wr + wv > real(0) ? wr / (wr + wv) : real(1);
  s.total = real(0.5) * k.alphaP * (wr + wv);
  return s;
}

// A distance r ∈ [0, R] with density R_d(r) 2πr / total on [0, R] (the paper's §4): ξ below the real
// source's probability picks it (and is rescaled to [0, 1) for its CDF), otherwise the virtual one.
TALLOW_FN DipoleInversion dipoleSampleRadius(DipoleSampler s, real xi) {
  real x = min(max(xi, real(0)), DIPOLE_XI_MAX);
  if (x < s.probReal) return dipoleInvertTerm(s.k.zr, s.k.sigmaTr, min(x / s.probReal, DIPOLE_XI_MAX) * s.shareReal);
  real rest = (x - s.probReal) / max(real(1) - s.probReal, real(1e-30));
  return dipoleInvertTerm(s.k.zv, s.k.sigmaTr, min(rest, DIPOLE_XI_MAX) * s.shareVirtual);
}

// The sampler's density per unit area of the plane [mm⁻²] at distance r: R_d(r)/total inside the
// disc, 0 outside it (and 0 for a medium that does not scatter, α' = 0, whose R_d is 0).
TALLOW_FN real dipoleAreaPdf(DipoleSampler s, real r) {
  if (!(r <= s.radius) || !(s.total > real(0))) return real(0);
  return standardDipoleRd(r, s.k).sd / s.total;
}

// Uniform samples on the same disc (the image-space paper's §6.1, "combined sampling"):
// r = R √ξ, density 1/(πR²).
TALLOW_FN real dipoleUniformRadius(real radius, real xi) { return radius * sqrt(min(max(xi, real(0)), real(1))); }
TALLOW_FN real dipoleUniformPdf(real radius, real r) {
  if (!(r <= radius) || !(radius > real(0))) return real(0);
  return real(1) / (BSSRDF_PI * radius * radius);
}
