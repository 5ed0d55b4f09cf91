// The quantities every BSSRDF model derives from the optical properties of one colour band,
// computed in one place (bssrdfCoefficients). Conventions: shaders/bssrdf/real.glsl.
#ifdef TALLOW_GLSL
#include "bssrdf/fresnel.glsl"
#endif

// Lower bound of α' in d_e = 2.131 D/√α' (Eq. 21): without scattering (σ_s = 0, which measured
// media such as Merlot have in some bands) d_e would be infinite; with the bound the virtual source
// sits ~10⁶ D away, where it contributes exactly 0 (e^{−σ_tr d_v} underflows), i.e. the limit.
const real BSSRDF_MIN_REDUCED_ALBEDO = 1e-12;
// The PBD clamp of the radiosity-maps paper (Dal Corso et al., §5, Fig. 14): distances to the
// sources are at least 0.25/(σ_a + σ_t) where they divide.
const real BSSRDF_PBD_CLAMP = 0.25;

struct BssrdfCoefficients {
  real sigmaA, sigmaS, g, eta;  // the inputs: σ_a, σ_s [mm⁻¹], mean cosine g, relative index η
  real sigmaT;    // σ_t = σ_a + σ_s
  real sigmaSp;   // σ_s' = σ_s (1 − g)         reduced scattering coefficient
  real sigmaTp;   // σ_t' = σ_a + σ_s'          reduced extinction coefficient
  real alphaP;    // α' = σ_s'/σ_t'              reduced albedo
  real D;         // D = 1/(3σ_t')              diffusion coefficient (Eq. 14)
  real sigmaTr;   // σ_tr = √(σ_a/D)            effective transport coefficient (Eq. 9)
  real de;        // d_e = 2.131 D/√α'          extrapolation distance (Eq. 21)
  real cPhi;      // C_φ(η)                     (appendix A, polynomial fit)
  real cE;        // C_E(η)
  real cPhiInv;   // C_φ(1/η)                   normalisation 1/(4C_φ(1/η)) of Eqs. 16, 20
  real A;         // A(η) = (1 − C_E)/(2C_φ)    reflection parameter (Eq. 22)
  // Standard dipole (Jensen et al. 2001, Eq. 5 and §2.4) with its own boundary term:
  real fdr;       // F_dr = −1.440/η² + 0.710/η + 0.668 + 0.0636η, η clamped to [1, 2.5]
  real aJensen;   // A = (1 + F_dr)/(1 − F_dr)
  real zr;        // z_r = 1/σ_t'               depth of the real source
  real zv;        // z_v = z_r + 4AD            height of the virtual source
  // Photon beam diffusion (Habel et al. 2013) with Grosjean's diffusion coefficient:
  real Dg;        // D_G = (2σ_a + σ_s')/(3σ_t'²)
  real sigmaTrG;  // σ_tr = √(σ_a/D_G)
  real zb;        // z_b = 2 A D_G              extrapolated boundary (A of Eq. 22)
  real pbdMinDistance;  // 0.25/(σ_a + σ_t)      the clamp of d_r in a denominator
};

// Requires σ_a, σ_s ≥ 0 with σ_a + σ_s > 0, |g| < 1, η > 0 (validateBssrdfConfig checks).
TALLOW_FN BssrdfCoefficients bssrdfCoefficients(real sigmaA, real sigmaS, real g, real eta) {
  BssrdfCoefficients k;
  k.sigmaA = sigmaA;
  k.sigmaS = sigmaS;
  k.g = g;
  k.eta = eta;
  k.sigmaT = sigmaA + sigmaS;
  k.sigmaSp = sigmaS * (real(1) - g);
  k.sigmaTp = sigmaA + k.sigmaSp;
  k.alphaP = k.sigmaSp / k.sigmaTp;
  k.D = real(1) / (real(3) * k.sigmaTp);
  k.sigmaTr = sqrt(sigmaA / k.D);
  k.de = real(2.131) * k.D / sqrt(max(k.alphaP, BSSRDF_MIN_REDUCED_ALBEDO));
  k.cPhi = cPhiPolynomial(eta);
  k.cE = cEPolynomial(eta);
  k.cPhiInv = cPhiPolynomial(real(1) / eta);
  k.A = (real(1) - k.cE) / (real(2) * k.cPhi);
  // Jensen et al.'s fit of the internal diffuse reflectance is for a denser medium; below η = 1 it
  // is negative (A < 0 below η ≈ 0.70) and above η ≈ 3.9 it exceeds 1, so it is clamped to [1, 2.5].
  real ej = clamp(eta, real(1), real(2.5));
  k.fdr = real(-1.440) / (ej * ej) + real(0.710) / ej + real(0.668) + real(0.0636) * ej;
  k.aJensen = (real(1) + k.fdr) / (real(1) - k.fdr);
  k.zr = real(1) / k.sigmaTp;
  k.zv = k.zr + real(4) * k.aJensen * k.D;
  k.Dg = (real(2) * sigmaA + k.sigmaSp) / (real(3) * k.sigmaTp * k.sigmaTp);
  k.sigmaTrG = sqrt(sigmaA / k.Dg);
  k.zb = real(2) * k.A * k.Dg;
  k.pbdMinDistance = BSSRDF_PBD_CLAMP / (sigmaA + k.sigmaT);
  return k;
}

// What a model evaluation returns: the raw diffusive part S_d [mm⁻²] and the scale against which
// its rounding error is measured: the sum of the absolute values of the terms whose signed sum is
// S_d (equal to |S_d| when nothing cancels; the real-minus-virtual source differences of the
// dipoles can cancel to far below the terms).
struct BssrdfEval {
  real sd;
  real scale;
};
