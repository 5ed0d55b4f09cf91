// The multiple-scattering term of photon beam diffusion (Habel, Christensen and Jarosz 2013,
// "PBD"; equation numbers are that paper's, "[cid]" those of its companion report "Classical and
// improved diffusion theory for subsurface scattering", Habel et al. 2013), with the distance clamp
// of the radiosity-maps paper (Dal Corso et al., §5 with Fig. 14). Conventions:
// shaders/bssrdf/real.glsl; coefficients: shaders/bssrdf/coefficients.glsl.
//
// The refracted beam x_r(t) = x_i + t ω12 (t ≥ 0 along the beam, depth z_r = t μ_i with
// μ_i = −ω12·n_i) is a continuum of point sources of strength Q(t) = σ_s' e^{−σ_t' t} ([cid] Eq. 23).
// Each is mirrored in the extrapolated boundary, the plane at height z_b = 2A D_G above x_i's
// tangent plane: x_v(t) = x_r(t) + 2(z_r + z_b) n_i. With d_r = |x_o − x_r|, d_v = |x_o − x_v| the
// exitance of one dipole is (PBD Eq. 5 = [cid] Eqs. 26–27, i.e. Eq. 18 of the directional-dipole
// paper applied to the point-source dipole):
//   M(t) = α'/(4π) [ C_φ/D_G (e^{−σ_tr d_r}/d_r − e^{−σ_tr d_v}/d_v)
//                  + C_E ((x_o − x_r)·n_o (1 + σ_tr d_r) e^{−σ_tr d_r}/d_r³
//                       − (x_o − x_v)·n_o (1 + σ_tr d_v) e^{−σ_tr d_v}/d_v³) ],
// which for x_o on the tangent plane and n_o = n_i is Habel's z_r(…)/d_r³ + (z_r + 2z_b)(…)/d_v³.
// The beam integral (PBD Eq. 10, its MIS estimator Eq. 11) with the correction κ of PBD Eq. 12,
//   M_d = ∫₀^∞ Q(t) κ(t) M(t) dt,   κ(t) = 1 − e^{−2σ_t'(d_r + t)},
// is normalised like the directional dipole (Eqs. 16, 20): S_d = M_d/(4π C_φ(1/η)). As in the
// radiosity-maps paper, every d_r in a denominator is clamped to ≥ 0.25/(σ_a + σ_t) (otherwise
// M_d diverges logarithmically as x_o approaches the beam); d_v is clamped the same way, which
// changes nothing on a planar surface (there d_v ≥ 2z_b > 0.25/(σ_a + σ_t)) and keeps x_o outside
// the medium finite. Exponentials and κ use the unclamped distances.
//
// Quadrature (deterministic, so that the GPU and the CPU agree and the result converges): the
// integrand is analytic in t except at kinks of the clamps and near-singular where x_o is close
// to the real or the virtual beam line (at t*, distance h: complex singularities at t* ± ih).
// [0, T_end] is cut at 0, the two closest approaches t_r*, t_v*, the clamp kinks
// t* ± √(c² − h²) and T_end = max(0, t_r*, t_v*) + 36/σ_t'; each piece is halved, and each half is
// integrated from its end with t = e ± ρ sinh(u), ρ = min(distance from e to the nearest complex
// singularity, 1/(σ_t' + σ_tr)), in panels of equal width in u, 8 Gauss–Legendre nodes each. Panel
// sizes then grow in proportion to the distance from the nearest singularity, which is what a
// nearly singular integrand needs. panelsPerEfold panels cover each unit of u (each e-fold of that
// distance). The default, 2 (16 nodes per e-fold), agrees with 8 panels per e-fold to < 1e-9 of
// the integral of |Q κ M| (the scale, = S_d where nothing cancels) on 2·10⁴ configurations with
// σ_a 1e-4–10, σ_s 1e-2–100 mm⁻¹, |g| < 0.99, η 0.5–2, |x_o − x_i| 1e-5–100 mm, on and off the
// beams (1 panel per e-fold: < 3e-7); tests/bssrdf_test.cpp checks 1e-6 against that reference and
// against an adaptive Gauss–Kronrod integration of Habel's planar formula. An evaluation with x_o
// on the surface uses 130–370 nodes (median 180; ~15 µs in double on one core).

#ifdef TALLOW_GLSL
#include "bssrdf/coefficients.glsl"
#endif

const int PBD_DEFAULT_PANELS_PER_EFOLD = 2;
const int PBD_MAX_PANELS_PER_HALF = 64;     // a bound for GPU loops; reached only at > 30 e-folds
const real PBD_TAIL_MEAN_FREE_PATHS = 36.0;  // e^{−36} ≈ 2e-16 of the beam is left past T_end
const real PBD_MIN_PEAK_WIDTH = 1e-4;        // h is taken as ≥ 1e-4 · clamp distance in the map

// 8-point Gauss–Legendre rule on [−1, 1]: the positive nodes and their weights.
const real PBD_GL_NODE[4] = {0.18343464249564980, 0.52553240991632899, 0.79666647741362674, 0.96028985649753623};
const real PBD_GL_WEIGHT[4] = {0.36268378337836198, 0.31370664587788729, 0.22238103445337447, 0.10122853629037626};

// Per-evaluation constants of the beam integral.
struct PbdBeam {
  real3 x;         // x_o − x_i
  real3 w12;       // beam direction ω12
  real3 ni;
  real3 no;
  real muI;        // μ_i = −ω12·n_i: depth per unit length along the beam
  real tReal;      // closest approach of x_o to the real beam line: parameter …
  real hReal;      // … and distance (≥ PBD_MIN_PEAK_WIDTH · c)
  real tVirtual;   // the same for the virtual line x_i + 2z_b n_i + t (ω12 + 2μ_i n_i)
  real hVirtual;
  real decayLength;  // 1/(σ_t' + σ_tr): the shortest length on which the integrand decays
};

// Q(t) κ(t) M(t) and, in .y, the same with |·| on every term (the scale of its rounding error).
TALLOW_FN real2 pbdIntegrand(real t, PbdBeam b, BssrdfCoefficients k) {
  real3 xr = b.x - t * b.w12;                               // x_o − x_r(t)
  real zr = t * b.muI;                                      // depth of x_r(t)
  real3 xv = xr - (real(2) * (zr + k.zb)) * b.ni;           // x_o − x_v(t)
  real dr = length(xr);
  real dv = length(xv);
  real drc = max(dr, k.pbdMinDistance);
  real dvc = max(dv, k.pbdMinDistance);
  real sr = k.sigmaTrG * dr;
  real sv = k.sigmaTrG * dv;
  real er = exp(-sr);
  real ev = exp(-sv);
  real phiR = er / drc;
  real phiV = ev / dvc;
  real fluxR = (real(1) + sr) * er / (drc * drc * drc) * dot(xr, b.no);
  real fluxV = (real(1) + sv) * ev / (dvc * dvc * dvc) * dot(xv, b.no);
  real kappa = real(1) - exp(real(-2) * k.sigmaTp * (dr + t));
  real f = k.sigmaSp * exp(-k.sigmaTp * t) * kappa * k.alphaP / (real(4) * BSSRDF_PI);
  real a = k.cPhi / k.Dg;
  return f * real2(a * (phiR - phiV) + k.cE * (fluxR - fluxV), a * (phiR + phiV) + k.cE * (abs(fluxR) + abs(fluxV)));
}

// Distance from beam parameter t to the nearest complex singularity of the integrand, at most
// the decay length.
TALLOW_FN real pbdLocalScale(real t, PbdBeam b) {
  real dtr = t - b.tReal;
  real dtv = t - b.tVirtual;
  real s = min(sqrt(dtr * dtr + b.hReal * b.hReal), sqrt(dtv * dtv + b.hVirtual * b.hVirtual));
  return min(s, b.decayLength);
}

// ∫ over [e, e + len] (dir = 1) or [e − len, e] (dir = −1), nodes graded away from e:
// t = e + dir ρ sinh(u), u ∈ [0, asinh(len/ρ)].
TALLOW_FN real2 pbdIntegrateFrom(real e, real dir, real len, PbdBeam b, BssrdfCoefficients k, int panelsPerEfold) {
  real rho = pbdLocalScale(e, b);
  real uEnd = asinh(len / rho);
  // Clamp in floating point before converting: a NaN or huge value must not reach int().
  real panels = ceil(uEnd * real(panelsPerEfold));
  int n = panels >= real(1) ? int(min(panels, real(PBD_MAX_PANELS_PER_HALF))) : 1;
  real du = uEnd / real(n);
  real2 sum = real2(0);
  for (int p = 0; p < n; ++p) {
    real uMid = (real(p) + real(0.5)) * du;
    for (int j = 0; j < 4; ++j) {
      real offset = real(0.5) * du * PBD_GL_NODE[j];
      real w = real(0.5) * du * PBD_GL_WEIGHT[j] * rho;
      real uA = uMid - offset;
      real uB = uMid + offset;
      sum += (w * cosh(uA)) * pbdIntegrand(e + dir * rho * sinh(uA), b, k);
      sum += (w * cosh(uB)) * pbdIntegrand(e + dir * rho * sinh(uB), b, k);
    }
  }
  return sum;
}

// S_d of photon beam diffusion, raw (it can be negative where x_o sees the virtual beam more
// than the real one, e.g. off the tangent plane). panelsPerEfold ≥ 1 (PBD_DEFAULT_PANELS_PER_EFOLD).
TALLOW_FN BssrdfEval photonBeamDiffusion(real3 xi, real3 ni, real3 wi, real3 xo, real3 no, BssrdfCoefficients k,
                                         int panelsPerEfold) {
  PbdBeam b;
  b.x = xo - xi;
  b.w12 = refractedDirection(wi, ni, k.eta);
  b.ni = ni;
  b.no = no;
  b.muI = max(-dot(b.w12, ni), real(0));
  real c = k.pbdMinDistance;
  real hMin = PBD_MIN_PEAK_WIDTH * c;
  b.tReal = dot(b.x, b.w12);
  real hr = length(b.x - b.tReal * b.w12);
  b.hReal = max(hr, hMin);
  real3 wv = b.w12 + (real(2) * b.muI) * ni;  // the virtual line's direction (unit)
  real3 y = b.x - (real(2) * k.zb) * ni;       // x_o relative to the virtual line's origin
  b.tVirtual = dot(y, wv);
  real hv = length(y - b.tVirtual * wv);
  b.hVirtual = max(hv, hMin);
  b.decayLength = real(1) / (k.sigmaTp + k.sigmaTrG);
  real tEnd = max(max(b.tReal, b.tVirtual), real(0)) + PBD_TAIL_MEAN_FREE_PATHS / k.sigmaTp;

  // Breakpoints: 0, T_end, the closest approaches and the clamp kinks inside (0, T_end).
  real cand[6];
  cand[0] = b.tReal;
  cand[1] = b.tVirtual;
  real kr = hr < c ? sqrt(c * c - hr * hr) : real(0);
  real kv = hv < c ? sqrt(c * c - hv * hv) : real(0);
  cand[2] = b.tReal - kr;
  cand[3] = b.tReal + kr;
  cand[4] = b.tVirtual - kv;
  cand[5] = b.tVirtual + kv;
  real bp[8];
  bp[0] = real(0);
  int nb = 1;
  for (int i = 0; i < 6; ++i) {
    if (cand[i] > real(0) && cand[i] < tEnd) {
      bp[nb] = cand[i];
      nb += 1;
    }
  }
  bp[nb] = tEnd;
  nb += 1;
  for (int i = 1; i < nb; ++i) {  // insertion sort
    real v = bp[i];
    int j = i - 1;
    while (j >= 0 && bp[j] > v) {
      bp[j + 1] = bp[j];
      j -= 1;
    }
    bp[j + 1] = v;
  }

  real2 sum = real2(0);
  for (int i = 0; i + 1 < nb; ++i) {
    real halfLen = real(0.5) * (bp[i + 1] - bp[i]);
    if (halfLen > real(0)) {
      sum += pbdIntegrateFrom(bp[i], real(1), halfLen, b, k, panelsPerEfold);
      sum += pbdIntegrateFrom(bp[i + 1], real(-1), halfLen, b, k, panelsPerEfold);
    }
  }
  real norm = real(1) / (real(4) * BSSRDF_PI * k.cPhiInv);
  BssrdfEval e;
  e.sd = sum.x * norm;
  e.scale = sum.y * norm;
  return e;
}
