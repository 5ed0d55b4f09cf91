// The spherical-harmonics arithmetic of SSLPV (Børlum et al. 2011, "the paper"; equation numbers
// are theirs), written once for the GPU passes (shaders/sslpv/*) and for C++ (sss/peers/sslpv_math.cpp,
// the tests), in the subset of common/shared.glsl. Two bands (l ≤ 1, the paper's §4): an
// intensity distribution I(ω) [W/sr] is c = (c00, c1−1, c10, c11) in the real basis
//   y00 = 1/√(4π),  y1−1 = √(3/4π) ω_y,  y10 = √(3/4π) ω_z,  y11 = √(3/4π) ω_x
// (the paper's e0…e3: sinθ sinφ = ω_y, cosθ = ω_z, sinθ cosφ = ω_x), so that c1−1, c10, c11
// are √(3/4π) times the y, z, x components of ∫ I(ω) ω dω.
#include "common/shared.glsl"

const float SSLPV_PI = 3.14159265358979f;
const float SSLPV_Y0 = 0.28209479177f;  // y00 = 1/(2√π)
const float SSLPV_Y1 = 0.48860251190f;  // √(3/(4π))

// The four basis functions at the unit direction w.
TALLOW_FN vec4 sslpvBasis(vec3 w) { return vec4(SSLPV_Y0, SSLPV_Y1 * w.y, SSLPV_Y1 * w.z, SSLPV_Y1 * w.x); }

// The intensity c evaluated in direction w: Σ c_lm y_lm(w).
TALLOW_FN float sslpvEvaluate(vec4 c, vec3 w) { return dot(c, sslpvBasis(w)); }

// Projection of the clamped cosine lobe max(0, a·ω)/π about the unit vector a (total flux 1):
// ∫ y00 max(0, a·ω)/π dω = y00 and ∫ y1m max(0, a·ω)/π dω = (2/3) √(3/4π) a_m. The injection
// (Eq. 1) and the propagation's face lobes (§3.2, §4) use it.
TALLOW_FN vec4 sslpvCosineLobe(vec3 a) {
  float k = 2.0f / 3.0f * SSLPV_Y1;
  return vec4(SSLPV_Y0, k * a.y, k * a.z, k * a.x);
}

// Total flux of an intensity distribution, Φ = ∫ I dω = 4π y00 c00 = 2√π c00 [W].
TALLOW_FN float sslpvFlux(vec4 c) { return 4.0f * SSLPV_PI * SSLPV_Y0 * c[0]; }

// Eq. 1: the intensity of the virtual point light of one texel, (1/π) T Φ_p max(0, ω_t·ω), from
// its transmitted flux T Φ_p [W] and the refracted direction ω_t (unit, into the medium).
TALLOW_FN vec4 sslpvInjectedIntensity(float transmittedFlux, vec3 wt) { return transmittedFlux * sslpvCosineLobe(wt); }

// §3.1: the solid angle of one texel of a light's shadow map seen from the light,
// Δω_p = 4α tan²(FOV/2) cos³θ_p / (N_x N_y), θ_p between the map's normal and the texel's ray.
TALLOW_FN float sslpvTexelSolidAngle(float cosTheta, float tanHalfFov, float aspect, float nx, float ny) {
  return 4.0f * aspect * tanHalfFov * tanHalfFov * cosTheta * cosTheta * cosTheta / (nx * ny);
}

// Eq. 3: scattering multiplies band l by (1 − σ'_s) + σ'_s g^l (Henyey–Greenstein moments g^l,
// the addition theorem: the phase function is diagonal in the SH basis).
TALLOW_FN vec4 sslpvScatter(vec4 c, float sigmaPrime, float g) {
  float band1 = (1.0f - sigmaPrime) + sigmaPrime * g;
  return vec4(c[0], band1 * c[1], band1 * c[2], band1 * c[3]);
}

// --- The grid's medium from measured coefficients (docs/sslpv.md, "Absorption and scattering") ----
// The paper attenuates each transfer between neighbouring cells by exp(−σ_t ΔX) (§3.2.1) and
// scatters by Eq. 3 with a dimensionless σ'_s ∈ [0, 1] (§3.2.2), and leaves both to the artist.
// From σ_a, σ_s, g [mm⁻¹] and the cell width ΔX [mm] we take:
//  * the survival of one step, exp(−σ_t ΔX) = min(e^{−σ_a ΔX}, 3/(cosh(σ_tr ΔX) + 2)): in a cell
//    thinner than a transport mean free path light travels about ΔX per step and only absorption
//    removes it; in a thick cell it diffuses, and a walk over the six neighbours that keeps a of
//    its flux per step decays as e^{−κx} with cosh(κ ΔX) = 3/a − 2, so this a gives κ = σ_tr,
//    the decay of diffusion theory (σ_tr = √(3 σ_a σ_t'), σ_t' = σ_a + σ_s(1 − g));
//  * σ'_s = 1 − e^{−σ_s ΔX}, the chance that light crossing a cell scatters in it.
TALLOW_FN float sslpvSurvival(float sigmaA, float sigmaS, float g, float cellMm) {
  float sigmaTp = sigmaA + sigmaS * (1.0f - g);
  float sigmaTr = sqrt(max(3.0f * sigmaA * sigmaTp, 0.0f));
  float diffusive = 3.0f / (cosh(min(sigmaTr * cellMm, 80.0f)) + 2.0f);
  return min(exp(-sigmaA * cellMm), diffusive);
}

// The grid's extinction σ_t [mm⁻¹] of §3.2.1: exp(−σ_t ΔX) is sslpvSurvival.
TALLOW_FN float sslpvGridExtinction(float sigmaA, float sigmaS, float g, float cellMm) {
  return -log(max(sslpvSurvival(sigmaA, sigmaS, g, cellMm), 1e-30f)) / cellMm;
}

// σ'_s of Eq. 2: the share of the light crossing a cell that scatters in it.
TALLOW_FN float sslpvScatteringFraction(float sigmaS, float cellMm) { return 1.0f - exp(-sigmaS * cellMm); }

// One source cell's coefficients as they leave it (§3.2): attenuated by exp(−σ_t ΔX), then
// scattered (Eq. 3, applied "prior to the propagation step").
TALLOW_FN vec4 sslpvAttenuateAndScatter(vec4 c, float sigmaT, float sigmaPrime, float g, float cellMm) {
  return exp(-sigmaT * cellMm) * sslpvScatter(c, sigmaPrime, g);
}

// --- Rendering (§3.3) --------------------------------------------------------------------------
// Eq. 6: the coefficients in the frame of the unit surface normal n, c^(n) = R_SH(α, β, γ)⁻¹ c, with
// the zyz Euler angles tan α = n_y/n_x, cos β = n_z, γ = 0 (the paper). For l = 1 the passive
// rotation takes the band's vector (c11, c1−1, c10) onto the rotated axes x' = (cos α cos β,
// sin α cos β, −sin β), y' = (−sin α, cos α, 0), z' = n; its third row is the paper's
// c10^(n) = sin α sin β c1−1 + cos β c10 + cos α sin β c11. sin α, cos α are taken from n_x, n_y
// directly (atan(0, 0) is undefined in GLSL); at the poles α = 0.
TALLOW_FN vec4 sslpvRotateToNormal(vec4 c, vec3 n) {
  float sinB = sqrt(max(n.x * n.x + n.y * n.y, 0.0f));
  float cosB = n.z;
  float cosA = sinB > 1e-7f ? n.x / sinB : 1.0f;
  float sinA = sinB > 1e-7f ? n.y / sinB : 0.0f;
  vec3 v = vec3(c[3], c[1], c[2]);  // (x, y, z) components of band 1
  vec3 xr = vec3(cosA * cosB, sinA * cosB, -sinB);
  vec3 yr = vec3(-sinA, cosA, 0.0f);
  vec3 zr = vec3(cosA * sinB, sinA * sinB, cosB);
  return vec4(c[0], dot(v, yr), dot(v, zr), dot(v, xr));
}

// Eqs. 5 and 7 for l ≤ 1: the radiance L_i of the uniform area light of area A [m²] that emits the
// flux the cell's point light sends into the polar cap θ ≤ θ_c about the normal,
//   L_i = (1/(Aπ)) ∫_cap I dω = (2/A) (c00 y00 (1 − cos θ_c) + c10^(n) √(3/4π) (1 − cos²θ_c)/2).
// cos θ_c = 0 is the paper's hemisphere (its final formula: (2/A)(√(1/4π) c00 + ½√(3/4π) c10));
// cos θ_c = 2/3 is the cap of 2π/3 sr, the solid angle of one face of a cube seen from its centre
// (sslpv.exitance = face, docs/sslpv.md).
TALLOW_FN float sslpvAreaLightRadiance(vec4 cn, float area, float capCos) {
  float band0 = cn[0] * SSLPV_Y0 * (1.0f - capCos);
  float band1 = cn[2] * SSLPV_Y1 * 0.5f * (1.0f - capCos * capCos);
  return 2.0f / area * (band0 + band1);
}
