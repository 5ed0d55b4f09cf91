// One entry point for the three BSSRDF models, with the reciprocal variant and the clamp.
// Conventions: shaders/bssrdf/real.glsl. The model numbers match sss::BssrdfModel.
#ifdef TALLOW_GLSL
#include "bssrdf/standard_dipole.glsl"
#include "bssrdf/directional_dipole.glsl"
#include "bssrdf/photon_beam_diffusion.glsl"
#endif

const int BSSRDF_MODEL_STANDARD = 0;     // Jensen et al. 2001
const int BSSRDF_MODEL_DIRECTIONAL = 1;  // Frisvad et al. 2014
const int BSSRDF_MODEL_PBD = 2;          // Habel et al. 2013

// The raw diffusive part S_d(x_i, w_i; x_o) of `model` [mm⁻²]: one colour band, coefficients from
// bssrdfCoefficients. The Fresnel transmittances T12, T21 are not included (Eq. 3).
//
// Total internal reflection at x_i (η < 1 and w_i beyond the critical angle): no light is
// refracted into the medium (T12 = 0), so the ray source of the directional dipole and the beam
// of photon beam diffusion do not exist and S_d = 0. (The standard dipole ignores w_i.)
TALLOW_FN BssrdfEval bssrdfEvaluate(int model, real3 xi, real3 ni, real3 wi, real3 xo, real3 no, BssrdfCoefficients k,
                                    int pbdPanelsPerEfold) {
  if (model != BSSRDF_MODEL_STANDARD && transmittedCos2(min(abs(dot(wi, ni)), real(1)), k.eta) <= real(0)) {
    BssrdfEval none;
    none.sd = real(0);
    none.scale = real(0);
    return none;
  }
  if (model == BSSRDF_MODEL_DIRECTIONAL) return directionalDipole(xi, ni, wi, xo, no, k);
  if (model == BSSRDF_MODEL_PBD) return photonBeamDiffusion(xi, ni, wi, xo, no, k, pbdPanelsPerEfold);
  return standardDipole(xi, xo, k);
}

// The reciprocal variant (directional-dipole paper §6.3): the average of S_d and S_d with the
// points of incidence and emergence swapped. The swapped evaluation needs a direction of
// incidence at x_o, which S_d(x_i, w_i; x_o) has no argument for (the emergent light is assumed
// diffuse, §3.2): it uses w_o = n_o, the mean direction of the cosine-weighted exitance. So
//   S_rec = ½ [S_d(x_i, n_i, w_i; x_o, n_o) + S_d(x_o, n_o, n_o; x_i, n_i)],
// exactly symmetric under the swap when w_i = n_i. The standard dipole is reciprocal already.
TALLOW_FN BssrdfEval bssrdfEvaluateReciprocal(int model, real3 xi, real3 ni, real3 wi, real3 xo, real3 no,
                                              BssrdfCoefficients k, int pbdPanelsPerEfold) {
  BssrdfEval a = bssrdfEvaluate(model, xi, ni, wi, xo, no, k, pbdPanelsPerEfold);
  if (model == BSSRDF_MODEL_STANDARD) return a;
  BssrdfEval b = bssrdfEvaluate(model, xo, no, no, xi, ni, k, pbdPanelsPerEfold);
  BssrdfEval e;
  e.sd = real(0.5) * (a.sd + b.sd);
  e.scale = real(0.5) * (a.scale + b.scale);
  return e;
}

// The value a renderer uses (directional-dipole paper §6.1): negative raw values clamped to 0.
TALLOW_FN real bssrdfClamped(real sd) { return max(sd, real(0)); }
