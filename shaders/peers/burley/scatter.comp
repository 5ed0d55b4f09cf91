#version 450 core
// burley.scatter (sss/peers/burley.h): per translucent pixel x_o of the camera's irradiance G-buffer,
// the radiosity of Christensen and Burley's normalised diffusion profile as engines compute it in
// screen space (Xie et al. 2020, Unreal's Burley SSS):
//   B(x_o) = A · Σ_j w_j E(p_j) / Σ_j w_j,   w_j = R(|p_j − x_o|) / q(r_j),
// per colour band, with N samples on a disc facing the camera: r_j drawn from one band's radius
// density (the bands in turn), q(r) the density of the three bands' mixture per unit area, the
// world radius projected into pixels at x_o's depth; a sample counts where its pixel shows the same
// object, at the distance between the two points (a depth step lowers its weight). The weights are
// renormalised over the samples that counted, so the samples lost off the object's edge do not
// darken it (what engines do); without any, B = A E(x_o). Then the light through thin parts: per
// light behind x_o, E_back · F_t · T(t) with t the thickness between x_o and the first surface the
// light's shadow map sees (profile.glsl's transmittance).
#include "peers/burley/transmission.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = 0) writeonly uniform image2D uRadiosity;

uniform sampler2D uIrradiance;
uniform int uSamples;  // N
uniform int uFrame;    // rotates the samples

const float BURLEY_TWO_PI = 6.28318530717958647692;

// Three uniform numbers in [0, 1) for sample j of pixel px in frame f (a PCG hash; Jarzynski and
// Olano 2020).
uvec3 burleyHash(uvec3 v) {
  v = v * 1664525u + 1013904223u;
  v.x += v.y * v.z;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  v ^= v >> 16u;
  v.x += v.y * v.z;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  return v;
}

vec3 burleyRandom(ivec2 px, int f, int j) {
  uvec3 h = burleyHash(uvec3(uint(px.x) | (uint(j) << 16u), uint(px.y) | (uint(f) << 16u), uint(j) ^ (uint(f) << 8u)));
  return vec3(h >> 8u) * (1.0 / 16777216.0);
}

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = textureSize(uPosition, 0);
  if (any(greaterThanEqual(px, size))) return;
  vec4 centre = texelFetch(uPosition, px, 0);
  int slot = int(centre.w + 0.5) - 1;
  if (slot < 0 || slot >= BURLEY_MAX_SLOTS) {
    imageStore(uRadiosity, px, vec4(0.0));
    return;
  }
  vec3 xo = centre.xyz;
  BurleyBand b0 = slotBand(slot, 0), b1 = slotBand(slot, 1), b2 = slotBand(slot, 2);
  vec3 d = vec3(b0.d, b1.d, b2.d);  // [mm]
  float footprint = pixelFootprint(xo);  // metres per pixel at x_o
  vec3 eo = texelFetch(uIrradiance, px, 0).rgb;
  vec3 weightSum = vec3(0.0), sum = vec3(0.0);
  for (int j = 0; j < uSamples; ++j) {
    vec3 u = burleyRandom(px, uFrame, j);
    int band = j % 3;
    float r = burleySampleRadius(u.x, u.y, d[band]);  // [mm], on the disc
    float angle = BURLEY_TWO_PI * u.z;
    vec2 offset = (r / BURLEY_MM_PER_M / footprint) * vec2(cos(angle), sin(angle));
    ivec2 q = ivec2(floor(vec2(px) + 0.5 + offset));
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
    vec4 hit = texelFetch(uPosition, q, 0);
    if (int(hit.w + 0.5) != slot + 1) continue;  // another object, an opaque one or nothing
    // The distance between the surface points; within x_o's own pixel the sampled one.
    float rs = q == px ? r : max(length(hit.xyz - xo) * BURLEY_MM_PER_M, 1e-6);
    float density = (burleyRadiusPdf(r, d.x) + burleyRadiusPdf(r, d.y) + burleyRadiusPdf(r, d.z)) /
                    (3.0 * BURLEY_TWO_PI * max(r, 1e-6));
    vec3 w = vec3(burleyProfile(rs, b0), burleyProfile(rs, b1), burleyProfile(rs, b2)) / density;
    weightSum += w;
    sum += w * texelFetch(uIrradiance, q, 0).rgb;
  }
  vec3 albedo = vec3(b0.albedo, b1.albedo, b2.albedo);
  vec3 b = vec3(weightSum.x > 0.0 ? sum.x / weightSum.x : eo.x, weightSum.y > 0.0 ? sum.y / weightSum.y : eo.y,
                weightSum.z > 0.0 ? sum.z / weightSum.z : eo.z) * albedo;
  if (uTransmission != 0) b += transmitted(xo, normalize(texelFetch(uNormal, px, 0).xyz), uEta[slot], b0, b1, b2);
  imageStore(uRadiosity, px, vec4(b, 1.0));
}
