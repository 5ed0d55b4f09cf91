#version 450 core
// One propagation step of SSLPV (sss/peers/sslpv_propagation.h; the paper's §3.2, §4): each cell d
// gathers from its six neighbours s = d + offset the coefficients that leave them, attenuated by
// e^{−σ_t ΔX} (§3.2.1) and scattered (Eq. 3) with s's medium, through Σ'_f M_{f,d←s} (§4).
// Vacuum cells hold nothing. From step skip + 1 on, the result is added to the accumulation grid.
#include "peers/sslpv/sh.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

uniform sampler3D uSourceR, uSourceG, uSourceB;  // the propagation grid before this step
uniform sampler3D uExtinction;  // rgb σ_t [mm⁻¹], a: 1 inside the medium (sss/peers/sslpv_medium.h)
uniform sampler3D uScattering;  // rgb σ'_s
uniform sampler3D uAnisotropy;  // rgb g
uniform mat4 uPropagation[6];   // Σ'_f M_{f,d←s} per neighbour, in OFFSETS' order
uniform int uSize;
uniform float uCellMm;
uniform int uAccumulate;

layout(rgba32f, binding = 0) writeonly uniform image3D uTargetR;
layout(rgba32f, binding = 1) writeonly uniform image3D uTargetG;
layout(rgba32f, binding = 2) writeonly uniform image3D uTargetB;
layout(rgba32f, binding = 3) uniform image3D uAccumulationR;
layout(rgba32f, binding = 4) uniform image3D uAccumulationG;
layout(rgba32f, binding = 5) uniform image3D uAccumulationB;

const ivec3 OFFSETS[6] = ivec3[6](ivec3(1, 0, 0), ivec3(-1, 0, 0), ivec3(0, 1, 0), ivec3(0, -1, 0), ivec3(0, 0, 1),
                                  ivec3(0, 0, -1));

void main() {
  ivec3 d = ivec3(gl_GlobalInvocationID);
  if (any(greaterThanEqual(d, ivec3(uSize)))) return;
  vec4 r = vec4(0.0), g = vec4(0.0), b = vec4(0.0);
  if (texelFetch(uExtinction, d, 0).a > 0.5) {
    for (int k = 0; k < 6; ++k) {
      ivec3 s = d + OFFSETS[k];
      if (any(lessThan(s, ivec3(0))) || any(greaterThanEqual(s, ivec3(uSize)))) continue;
      vec4 sigmaT = texelFetch(uExtinction, s, 0);
      if (sigmaT.a < 0.5) continue;  // vacuum holds nothing
      vec3 sigmaPrime = texelFetch(uScattering, s, 0).rgb;
      vec3 aniso = texelFetch(uAnisotropy, s, 0).rgb;
      mat4 m = uPropagation[k];
      r += m * sslpvAttenuateAndScatter(texelFetch(uSourceR, s, 0), sigmaT.r, sigmaPrime.r, aniso.r, uCellMm);
      g += m * sslpvAttenuateAndScatter(texelFetch(uSourceG, s, 0), sigmaT.g, sigmaPrime.g, aniso.g, uCellMm);
      b += m * sslpvAttenuateAndScatter(texelFetch(uSourceB, s, 0), sigmaT.b, sigmaPrime.b, aniso.b, uCellMm);
    }
  }
  imageStore(uTargetR, d, r);
  imageStore(uTargetG, d, g);
  imageStore(uTargetB, d, b);
  if (uAccumulate != 0) {
    imageStore(uAccumulationR, d, imageLoad(uAccumulationR, d) + r);
    imageStore(uAccumulationG, d, imageLoad(uAccumulationG, d) + g);
    imageStore(uAccumulationB, d, imageLoad(uAccumulationB, d) + b);
  }
}
