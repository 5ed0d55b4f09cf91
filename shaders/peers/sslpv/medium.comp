#version 450 core
// SSLPV's medium grid (sss/peers/sslpv_medium.h, step 2): per LPV cell, which of its 2 × 2 × 2
// sub-samples are inside a translucent object (parity along at least two of the three axes) and
// the mean material of those; from it the grid's σ_t and σ'_s of §3.2.1–3.2.2 and g.
#include "peers/sslpv/sh.glsl"
#include "peers/sslpv/volume.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

const int MAX_SLOTS = 8;
uniform int uSlotCount;
uniform int uSize;      // N
uniform int uWords;     // 32-bit words per parity column
uniform vec3 uOrigin;   // m
uniform float uCell;    // m
uniform float uCellMm;  // mm
uniform vec3 uSigmaA[MAX_SLOTS];  // mm⁻¹ per band: each object's material
uniform vec3 uSigmaS[MAX_SLOTS];
uniform vec3 uG[MAX_SLOTS];
uniform int uVolume[MAX_SLOTS];   // 1: the object has a second material (volume.glsl)
uniform vec3 uInnerSigmaA[MAX_SLOTS];
uniform vec3 uInnerSigmaS[MAX_SLOTS];
uniform vec3 uInnerG[MAX_SLOTS];
uniform vec3 uVolumeAxis[MAX_SLOTS];
uniform vec4 uVolumeShape[MAX_SLOTS];  // period [m], fraction, turbulence, unused
uniform uint uVolumeSeed[MAX_SLOTS];
uniform mat4 uWorldToObject[MAX_SLOTS];

layout(r32ui, binding = 0) readonly uniform uimage2DArray uParity;
layout(rgba32f, binding = 1) writeonly uniform image3D uExtinction;  // rgb σ_t [mm⁻¹], a: 1 medium
layout(rgba32f, binding = 2) writeonly uniform image3D uScattering;  // rgb σ'_s, a: inside share
layout(rgba32f, binding = 3) writeonly uniform image3D uAnisotropy;  // rgb g

// The parity of sub-sample g (in 0 … 2N − 1 per axis) along `axis` for object `slot`.
bool insideAlong(int slot, int axis, ivec3 g) {
  int u = (axis + 1) % 3, v = (axis + 2) % 3;
  int bit = g[axis];
  uint word = imageLoad(uParity, ivec3(g[u], g[v], (slot * 3 + axis) * uWords + (bit >> 5))).r;
  return ((word >> uint(bit & 31)) & 1u) != 0u;
}

void main() {
  ivec3 cell = ivec3(gl_GlobalInvocationID);
  if (any(greaterThanEqual(cell, ivec3(uSize)))) return;
  vec3 sigmaA = vec3(0.0), sigmaS = vec3(0.0), g = vec3(0.0);
  int inside = 0;
  for (int s = 0; s < 8; ++s) {
    ivec3 sub = 2 * cell + ivec3(s & 1, (s >> 1) & 1, (s >> 2) & 1);
    for (int slot = 0; slot < uSlotCount; ++slot) {
      int votes = int(insideAlong(slot, 0, sub)) + int(insideAlong(slot, 1, sub)) + int(insideAlong(slot, 2, sub));
      if (votes < 2) continue;
      float w = 0.0;
      if (uVolume[slot] != 0) {
        vec3 x = uOrigin + (vec3(sub) + 0.5) * (0.5 * uCell);
        vec3 p = (uWorldToObject[slot] * vec4(x, 1.0)).xyz;
        vec4 shape = uVolumeShape[slot];
        w = sslpvVolumeWeight(p, uVolumeAxis[slot], shape.x, shape.y, shape.z, uVolumeSeed[slot]);
      }
      sigmaA += mix(uSigmaA[slot], uInnerSigmaA[slot], w);
      sigmaS += mix(uSigmaS[slot], uInnerSigmaS[slot], w);
      g += mix(uG[slot], uInnerG[slot], w);
      ++inside;
      break;  // the first object that holds the sub-sample
    }
  }
  if (inside == 0) {
    imageStore(uExtinction, cell, vec4(0.0));
    imageStore(uScattering, cell, vec4(0.0));
    imageStore(uAnisotropy, cell, vec4(0.0));
    return;
  }
  float k = 1.0 / float(inside);
  sigmaA *= k;
  sigmaS *= k;
  g *= k;
  vec3 sigmaT, sigmaPrime;
  for (int c = 0; c < 3; ++c) {
    sigmaT[c] = sslpvGridExtinction(sigmaA[c], sigmaS[c], g[c], uCellMm);
    sigmaPrime[c] = sslpvScatteringFraction(sigmaS[c], uCellMm);
  }
  imageStore(uExtinction, cell, vec4(sigmaT, 1.0));
  imageStore(uScattering, cell, vec4(sigmaPrime, float(inside) / 8.0));
  imageStore(uAnisotropy, cell, vec4(g, 0.0));
}
