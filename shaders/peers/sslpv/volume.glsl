// Heterogeneous media for SSLPV (the paper's §3.2.1–3.2.2 store σ_t, σ'_s and g per cell): a
// second material in layers across an axis, warped by turbulence into veins as in Perlin's marble
// (Perlin 1985, "An image synthesizer": a sine of x plus turbulence; here the fractional part of
// the layer coordinate plus turbulence). Shared by the medium pass (shaders/peers/sslpv/medium.comp) and
// C++ (sss/peers/sslpv_math.h, the tests); conventions of common/shared.glsl, GLSL `uint` as 32-bit.
#include "common/shared.glsl"

// PCG hash: one step of PCG's 32-bit LCG and its RXS-M-XS output (O'Neill 2014; the GPU hash
// Jarzynski and Olano 2020 recommend), as in shaders/sss/estimator.glsl.
TALLOW_FN uint sslpvHash(uint v) {
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

// A value in [0, 1) per integer lattice point and seed (the top 24 bits, exact in float).
TALLOW_FN float sslpvLatticeValue(ivec3 q, uint seed) {
  uint h = sslpvHash(uint(q.x) + sslpvHash(uint(q.y) + sslpvHash(uint(q.z) + sslpvHash(seed))));
  return float(h >> 8u) * (1.0f / 16777216.0f);
}

// Value noise in [0, 1): the lattice values interpolated trilinearly with the smooth weights
// 3t² − 2t³.
TALLOW_FN float sslpvValueNoise(vec3 p, uint seed) {
  vec3 f = floor(p);
  ivec3 i = ivec3(f);
  vec3 t = p - f;
  t = t * t * (vec3(3.0f) - 2.0f * t);
  float n = 0.0f;
  for (int c = 0; c < 8; ++c) {
    int dx = c & 1, dy = (c >> 1) & 1, dz = (c >> 2) & 1;
    float w = (dx == 1 ? t.x : 1.0f - t.x) * (dy == 1 ? t.y : 1.0f - t.y) * (dz == 1 ? t.z : 1.0f - t.z);
    n += w * sslpvLatticeValue(i + ivec3(dx, dy, dz), seed);
  }
  return n;
}

// Turbulence: Σ_{o<4} 2^{−o} |2 noise(2^o p) − 1|, in [0, 1.875].
TALLOW_FN float sslpvTurbulence(vec3 p, uint seed) {
  float sum = 0.0f, amplitude = 1.0f, frequency = 1.0f;
  for (int o = 0; o < 4; ++o) {
    sum += amplitude * abs(2.0f * sslpvValueNoise(frequency * p, seed + uint(o)) - 1.0f);
    amplitude *= 0.5f;
    frequency *= 2.0f;
  }
  return sum;
}

// The share of the second material at p [m, in the object's frame]: 1 where the layer coordinate
// t = (p·axis)/period + turbulence · turbulence(p/period) has fract(t) < fraction, else 0.
// turbulence = 0 gives flat layers of thickness fraction × period.
TALLOW_FN float sslpvVolumeWeight(vec3 p, vec3 axis, float period, float fraction, float turbulence, uint seed) {
  vec3 q = p / period;
  float t = dot(q, axis) + turbulence * sslpvTurbulence(q, seed);
  return fract(t) < fraction ? 1.0f : 0.0f;
}
