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
#include "common/lights.glsl"
#include "bssrdf/real.glsl"
#include "bssrdf/fresnel.glsl"
#include "peers/burley/profile.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = 0) writeonly uniform image2D uRadiosity;

const int BURLEY_MAX_SLOTS = 8;
uniform vec3 uSigmaA[BURLEY_MAX_SLOTS];
uniform vec3 uSigmaS[BURLEY_MAX_SLOTS];
uniform vec3 uG[BURLEY_MAX_SLOTS];
uniform float uEta[BURLEY_MAX_SLOTS];
uniform sampler2D uPosition;    // burley.gbuffer
uniform sampler2D uNormal;
uniform sampler2D uIrradiance;
uniform sampler2DArray uDirShadowDepth;      // the shadow maps as depths (compare mode off)
uniform samplerCubeArray uPointShadowDepth;
uniform vec3 uCameraPosition;
uniform int uCameraOrthographic;
uniform float uPixelScale;  // a pixel's world size: per metre of distance (perspective) or in metres
uniform int uSamples;       // N
uniform int uFrame;         // rotates the samples
uniform int uTransmission;

const float BURLEY_MM_PER_M = 1000.0;
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

// The thickness [m] between p and the first surface directional light i's shadow map sees along
// the light (−1: the light has no shadow map, or p lies outside it).
float directionalThickness(int i, vec3 p) {
  int layer = uDirShadowLayer[i];
  if (layer < 0) return -1.0;
  vec4 s = uDirShadowMatrix[i] * vec4(p, 1.0);
  if (any(lessThan(s.xyz, vec3(0.0))) || any(greaterThan(s.xyz, vec3(1.0)))) return -1.0;
  float first = texture(uDirShadowDepth, vec3(s.xy, float(layer))).r;
  mat4 m = uDirShadowMatrix[i];
  // z per metre along the light's direction: the projection's depth row against that direction.
  float slope = abs(dot(vec3(m[0][2], m[1][2], m[2][2]), uDirDirection[i]));
  return slope > 0.0 ? max(s.z - first, 0.0) / slope : -1.0;
}

// The same for point light i through its cube (common/cube_shadow_depth.glsl).
float pointThickness(int i, vec3 p) {
  int layer = uPointShadowLayer[i];
  if (layer < 0) return -1.0;
  vec3 d = p - uPointPosition[i];
  float m = max(max(abs(d.x), abs(d.y)), abs(d.z));
  if (!(m > 0.0)) return -1.0;
  float first = cubeShadowAxisDistance(texture(uPointShadowDepth, vec4(d, float(layer))).r, uPointShadowRange[i]);
  return max(m - first, 0.0) * length(d) / m;  // the axis component back to the distance along d
}

vec3 transmittance(float tMm, BurleyBand b0, BurleyBand b1, BurleyBand b2) {
  return vec3(burleyTransmittance(tMm, b0), burleyTransmittance(tMm, b1), burleyTransmittance(tMm, b2));
}

// The light reaching x_o through the object from the lights behind it (n faces the camera).
vec3 transmitted(vec3 xo, vec3 n, float eta, BurleyBand b0, BurleyBand b1, BurleyBand b2) {
  vec3 b = vec3(0.0);
  for (int i = 0; i < uDirCount; ++i) {
    float c = -dot(n, uDirDirection[i]);
    if (!(c > 0.0)) continue;
    float t = directionalThickness(i, xo);
    if (t < 0.0) continue;
    b += uDirIrradiance[i] * (c * fresnelTransmittance(c, eta)) * transmittance(t * BURLEY_MM_PER_M, b0, b1, b2);
  }
  for (int i = 0; i < uPointCount; ++i) {
    vec3 l = uPointPosition[i] - xo;
    float d2 = dot(l, l);
    float c = -dot(n, l) * inversesqrt(d2);
    if (!(c > 0.0)) continue;
    float t = pointThickness(i, xo);
    if (t < 0.0) continue;
    b += uPointIntensity[i] * (c * fresnelTransmittance(c, eta) / d2) * transmittance(t * BURLEY_MM_PER_M, b0, b1, b2);
  }
  return b;
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
  BurleyBand b0 = burleyBand(bssrdfCoefficients(uSigmaA[slot].x, uSigmaS[slot].x, uG[slot].x, uEta[slot]));
  BurleyBand b1 = burleyBand(bssrdfCoefficients(uSigmaA[slot].y, uSigmaS[slot].y, uG[slot].y, uEta[slot]));
  BurleyBand b2 = burleyBand(bssrdfCoefficients(uSigmaA[slot].z, uSigmaS[slot].z, uG[slot].z, uEta[slot]));
  vec3 d = vec3(b0.d, b1.d, b2.d);  // [mm]
  // Metres per pixel at x_o.
  float footprint = uCameraOrthographic != 0 ? uPixelScale : uPixelScale * length(xo - uCameraPosition);
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
