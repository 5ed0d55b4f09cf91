#version 450 core
// Evaluates one BSSRDF configuration per invocation with the shared model files, for
// `tallow probe bssrdf --gpu` and the GLSL-vs-C++ tests (sss/bssrdf/bssrdf_gpu.cpp).
#include "bssrdf/bssrdf.glsl"

layout(local_size_x = 64) in;

// One configuration (sss::BssrdfConfig in float), six vec4 so that std430 has no hidden padding.
struct ProbeConfig {
  vec4 xi;        // xyz: point of incidence [mm]
  vec4 ni;        // xyz: outward normal at x_i
  vec4 wi;        // xyz: unit vector from x_i toward the light
  vec4 xo;        // xyz: point of emergence [mm]
  vec4 no;        // xyz: outward normal at x_o
  vec4 material;  // σ_a [mm⁻¹], σ_s [mm⁻¹], g, η
};

layout(std430, binding = 0) readonly buffer ProbeConfigs { ProbeConfig configs[]; };
layout(std430, binding = 1) writeonly buffer ProbeResults { vec2 results[]; };  // raw S_d, clamped S_d

uniform int uCount;              // configurations in this dispatch
uniform int uModel;              // BSSRDF_MODEL_*
uniform int uReciprocal;         // 1: the reciprocal variant
uniform int uPbdPanelsPerEfold;  // photon beam diffusion quadrature

void main() {
  int i = int(gl_GlobalInvocationID.x);
  if (i >= uCount) return;
  ProbeConfig c = configs[i];
  BssrdfCoefficients k = bssrdfCoefficients(c.material.x, c.material.y, c.material.z, c.material.w);
  BssrdfEval e =
      uReciprocal != 0
          ? bssrdfEvaluateReciprocal(uModel, c.xi.xyz, c.ni.xyz, c.wi.xyz, c.xo.xyz, c.no.xyz, k, uPbdPanelsPerEfold)
          : bssrdfEvaluate(uModel, c.xi.xyz, c.ni.xyz, c.wi.xyz, c.xo.xyz, c.no.xyz, k, uPbdPanelsPerEfold);
  results[i] = vec2(e.sd, bssrdfClamped(e.sd));
}
