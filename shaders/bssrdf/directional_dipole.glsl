// The directional dipole (Frisvad, Hachisuka and Kjeldsen 2014; equation numbers are that
// paper's). Conventions: shaders/bssrdf/real.glsl; coefficients: shaders/bssrdf/coefficients.glsl.
#ifdef TALLOW_GLSL
#include "bssrdf/coefficients.glsl"
#endif

// Distances to the sources are at least this many diffusion lengths D where they divide. The
// model is singular at the sources: d_r → 0 needs x_o = x_i and μ0 → 0⁺ (S_d then grows like
// 1/(Dμ0)², overflowing float below μ0 ~ 1e-12), d_v = 0 needs x_o at the virtual source, outside
// the medium. The bound changes no value with d ≥ 10⁻⁴ D, and keeps every value finite.
const real DIRECTIONAL_MIN_DISTANCE = 1e-4;
// Frontlit (Eq. 24) when μ0 > this. Eq. 24 says μ0 > 0, and the model jumps there (the backlit d_r
// adds 1/(3σ_t)²); in float the sign of a |μ0| below ~1e-7 is rounding noise, and refraction under
// total internal reflection (η < 1) yields exactly μ0 = 0 on a plane, which must be backlit on every
// device alike.
const real DIRECTIONAL_FRONTLIT_MIN_MU0 = 1e-6;

// Eq. 9: fluence of a ray source along ω (unit) at offset x from its origin, per unit flux Φ,
// with r the distance that replaces |x| (Eq. 9 uses r = |x|, cos θ = x·ω/r; the model replaces r
// by the corrected d_r, §3.3.3):
//   φ'_d = 1/(4πD) e^{−σ_tr r}/r (1 + 3D (1 + σ_tr r)/r · (x·ω)/r).
TALLOW_FN real rayFluence(real3 x, real3 w, real r, BssrdfCoefficients k) {
  real sr = k.sigmaTr * r;
  real e = exp(-sr);
  if (e <= real(0)) return real(0);
  return e / (real(4) * BSSRDF_PI * k.D * r * r * r) * (r * r + real(3) * k.D * (real(1) + sr) * dot(x, w));
}

// Eq. 19: the gradient of Eq. 9 with respect to x (r = |x|; tested against finite differences):
//   ∇φ'_d = 1/(4πD) e^{−σ_tr r}/r³ (ω 3D(1 + σ_tr r) − x(1 + σ_tr r)
//                                    − x 3D (3(1 + σ_tr r) + (σ_tr r)²)/r² (x·ω)).
TALLOW_FN real3 rayFluenceGradient(real3 x, real3 w, real r, BssrdfCoefficients k) {
  real sr = k.sigmaTr * r;
  real e = exp(-sr);
  if (e <= real(0)) return real3(0);
  real onePlus = real(1) + sr;
  real3 g = (real(3) * k.D * onePlus) * w - onePlus * x -
            (real(3) * k.D * (real(3) * onePlus + sr * sr) / (r * r) * dot(x, w)) * x;
  return (e / (real(4) * BSSRDF_PI * k.D * r * r * r)) * g;
}

// Eq. 20: the diffusive BSSRDF of one ray source in an infinite medium,
//   S'_d(x, ω, r) = 1/(4C_φ(1/η)) · 1/(4π²) · e^{−σ_tr r}/r³ · [ C_φ(η)(r²/D + 3(1 + σ_tr r) x·ω)
//        − C_E(η)(3D(1 + σ_tr r) ω·n_o − ((1 + σ_tr r) + 3D (3(1 + σ_tr r) + (σ_tr r)²)/r² x·ω) x·n_o) ].
// Derivation (where the transcriptions differ). Eq. 18 gives the exitance
// M_d = C_φ φ − C_E D n_o·∇φ, and Eq. 16 S'_d = M_d/(4π C_φ(1/η) Φ). With Eq. 9 written as
// φ = Φ/(4πD) e^{−σr}/r³ (r² + 3D(1 + σr) x·ω) and Eq. 19,
//   C_φ φ     = Φ/(4π) e^{−σr}/r³ · C_φ (r²/D + 3(1 + σr) x·ω),
//   −C_E D n_o·∇φ = −Φ/(4π) e^{−σr}/r³ · C_E (3D(1 + σr) ω·n_o − (1 + σr) x·n_o
//                                              − 3D (3(1 + σr) + (σr)²)/r² (x·ω)(x·n_o)),
// so C_E multiplies the whole second bracket, the x·n_o term included, with the sign above. That
// is the directional-dipole paper's Eq. 20. The radiosity-maps paper's appendix A closes the C_E
// bracket after the ω·n_o term, which leaves the x·n_o term without C_E and with the opposite
// sign; tests/bssrdf_test.cpp checks Eq. 20 against Eqs. 16 + 18 built from Eqs. 9 and 19.
// .x: S'_d; .y: the same with |·| on each of the four terms of the bracket (its rounding scale).
TALLOW_FN real2 raySourceBssrdfTerms(real3 x, real3 w, real r, real3 no, BssrdfCoefficients k) {
  real sr = k.sigmaTr * r;
  real e = exp(-sr);
  if (e <= real(0)) return real2(0);  // also keeps 0 · ∞ out when r³ or (σ_tr r)² overflow
  real onePlus = real(1) + sr;
  real xw = dot(x, w);
  real xn = dot(x, no);
  real wn = dot(w, no);
  real t1 = k.cPhi * r * r / k.D;
  real t2 = k.cPhi * real(3) * onePlus * xw;
  real t3 = -k.cE * real(3) * k.D * onePlus * wn;
  real t4 = k.cE * (onePlus + real(3) * k.D * (real(3) * onePlus + sr * sr) / (r * r) * xw) * xn;
  real f = e / (real(16) * BSSRDF_PI * BSSRDF_PI * k.cPhiInv * r * r * r);
  return f * real2(t1 + t2 + t3 + t4, abs(t1) + abs(t2) + abs(t3) + abs(t4));
}

TALLOW_FN real raySourceBssrdf(real3 x, real3 w, real r, real3 no, BssrdfCoefficients k) {
  return raySourceBssrdfTerms(x, w, r, no, k).x;
}

// Eq. 23: the normal of the modified tangent plane, which contains x = x_o − x_i and is
// perpendicular to the plane spanned by n_i and x:
//   n_i* = x/|x| × (n_i × x)/|n_i × x|  = (n_i − (n_i·x̂) x̂)/|n_i − (n_i·x̂) x̂|,   n_i* = n_i for x_o = x_i.
// Eq. 23 leaves x ∥ n_i undefined (x_o straight above or below x_i); there, too, n_i* = n_i.
TALLOW_FN real3 modifiedTangentNormal(real3 x, real3 ni) {
  real3 v = cross(x, cross(ni, x));  // = n_i |x|² − x (n_i·x), of length |x|² sin∠(n_i, x)
  real len = length(v);
  if (len > real(1e-6) * dot(x, x) && len > real(0)) return v / len;
  return ni;
}

// Eqs. 24–25: the corrected distance to the real source, with μ0 = −n_o·ω12 and r = |x|:
//   frontlit (μ0 > 0; here μ0 > DIRECTIONAL_FRONTLIT_MIN_MU0):
//     d_r² = r² + Dμ0 (Dμ0 − 2 d_e cos β),  cos β = −√((r² − (x·ω12)²)/(r² + d_e²));
//   backlit (otherwise):  d_r² = r² + 1/(3σ_t)².
TALLOW_FN real directionalRealDistance(real3 x, real3 w12, real mu0, BssrdfCoefficients k) {
  real r2 = dot(x, x);
  if (mu0 > DIRECTIONAL_FRONTLIT_MIN_MU0) {
    real xw = dot(x, w12);
    real cosBeta = -sqrt(max(r2 - xw * xw, real(0)) / (r2 + k.de * k.de));
    real dmu = k.D * mu0;
    return sqrt(r2 + dmu * (dmu - real(2) * k.de * cosBeta));
  }
  real b = real(1) / (real(3) * k.sigmaT);
  return sqrt(r2 + b * b);
}

// The dipole's construction (Fig. 3, Eq. 26): the real ray source starts at x_i along ω12; the
// virtual one starts at x_v = x_i + 2A d_e n_i* along ω12 mirrored in the modified tangent plane.
struct DirectionalDipoleGeometry {
  real3 w12;     // refracted direction (fresnel.glsl)
  real mu0;      // μ0 = −n_o·ω12: frontlit when > 0
  real dr;       // corrected distance to the real source (Eqs. 24–25)
  real3 niStar;  // modified tangent-plane normal (Eq. 23)
  real3 xv;      // x_v − x_i = 2A d_e n_i*
  real3 wv;      // ω_v = ω12 − 2(ω12·n_i*) n_i*
  real dv;       // d_v = |x_o − x_v|
};

TALLOW_FN DirectionalDipoleGeometry directionalDipoleGeometry(real3 xi, real3 ni, real3 wi, real3 xo, real3 no,
                                                              BssrdfCoefficients k) {
  DirectionalDipoleGeometry g;
  real3 x = xo - xi;
  g.w12 = refractedDirection(wi, ni, k.eta);
  g.mu0 = -dot(no, g.w12);
  g.dr = directionalRealDistance(x, g.w12, g.mu0, k);
  g.niStar = modifiedTangentNormal(x, ni);
  g.xv = (real(2) * k.A * k.de) * g.niStar;
  g.wv = g.w12 - (real(2) * dot(g.w12, g.niStar)) * g.niStar;
  g.dv = length(x - g.xv);
  return g;
}

// Eq. 26: S_d(x_i, w_i; x_o) = S'_d(x_o − x_i, ω12, d_r) − S'_d(x_o − x_v, ω_v, d_v). Raw: it can be
// negative (§6.1); the caller clamps.
TALLOW_FN BssrdfEval directionalDipole(real3 xi, real3 ni, real3 wi, real3 xo, real3 no, BssrdfCoefficients k) {
  DirectionalDipoleGeometry g = directionalDipoleGeometry(xi, ni, wi, xo, no, k);
  real3 x = xo - xi;
  real minDistance = DIRECTIONAL_MIN_DISTANCE * k.D;
  real2 sReal = raySourceBssrdfTerms(x, g.w12, max(g.dr, minDistance), no, k);
  real2 sVirtual = raySourceBssrdfTerms(x - g.xv, g.wv, max(g.dv, minDistance), no, k);
  BssrdfEval e;
  e.sd = sReal.x - sVirtual.x;
  e.scale = sReal.y + sVirtual.y;
  return e;
}
