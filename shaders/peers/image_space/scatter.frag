#version 450 core
// image_space.scatter: per translucent pixel x_o, the scattered radiosity of the image-space paper
// (Eqs. 4, 8–9) by the combined samples of shaders/peers/image_space/sampling.glsl (drawn once per frame
// by pattern.comp; the pixel uses the set of its place in the T×T interleaving tile):
//   B(x_o) = Σ_j R_d(|x_o − p_j|) E(p_j) (dA_p/dA_p')_j weight_j   per colour band,
// p'_j = x_o + offset_j in x_o's tangent plane, projected into the camera image (§5); the pixel it
// falls in gives the surface there, and p_j is where the camera ray through p'_j meets that pixel's
// tangent plane (exact on planes; the pixel's centre would quantise r to the image grid). A sample
// counts only where that pixel shows the same translucent object and p_j lies near the tangent
// plane (|p_j − p'_j| ≤ depth_ratio · max(r', one pixel)): elsewhere it falls on another object, on
// nothing, or across a depth discontinuity onto a surface that is not x_o's neighbourhood, and
// contributes 0 (the paper's rejection of samples outside the depth image, extended to the other
// two cases). The coverage output sums the per-band coverage of the samples that counted.
#include "peers/image_space/sampling.glsl"
#include "peers/image_space/pattern.glsl"

in vec2 vUv;

const int IS_MAX_SLOTS = 8;
uniform vec3 uSigmaA[IS_MAX_SLOTS];
uniform vec3 uSigmaS[IS_MAX_SLOTS];
uniform vec3 uG[IS_MAX_SLOTS];
uniform float uEta[IS_MAX_SLOTS];
uniform sampler2D uPosition;    // image_space.gbuffer
uniform sampler2D uNormal;
uniform sampler2D uIrradiance;
uniform mat4 uViewProjection;
uniform vec3 uCameraPosition;
uniform vec3 uCameraForward;
uniform int uCameraOrthographic;
uniform float uPixelScale;      // a pixel's world size: per metre of distance (perspective) or in metres
uniform int uTile;              // T
uniform int uSamples;           // N
uniform float uDepthRatio;      // image_space.depth_ratio
uniform int uJacobian;          // image_space.jacobian

layout(std430, binding = 7) readonly buffer Pattern { IsPatternGpu pattern[]; };

layout(location = 0) out vec4 oSum;       // rgb: B of this pixel's sample set [W/m²]
layout(location = 1) out vec4 oCoverage;  // rgb: Σ coverage of the samples that found x_o's surface

const float IS_MM_PER_M = 1000.0;

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  oSum = vec4(0.0);
  oCoverage = vec4(0.0);
  vec4 centre = texelFetch(uPosition, px, 0);
  int slot = int(centre.w + 0.5) - 1;
  if (slot < 0) return;
  vec3 xo = centre.xyz;
  vec3 no = normalize(texelFetch(uNormal, px, 0).xyz);
  vec3 t1 = normalize(abs(no.x) < 0.9 ? cross(no, vec3(1.0, 0.0, 0.0)) : cross(no, vec3(0.0, 1.0, 0.0)));
  vec3 t2 = cross(no, t1);
  BssrdfCoefficients k0 = bssrdfCoefficients(uSigmaA[slot].x, uSigmaS[slot].x, uG[slot].x, uEta[slot]);
  BssrdfCoefficients k1 = bssrdfCoefficients(uSigmaA[slot].y, uSigmaS[slot].y, uG[slot].y, uEta[slot]);
  BssrdfCoefficients k2 = bssrdfCoefficients(uSigmaA[slot].z, uSigmaS[slot].z, uG[slot].z, uEta[slot]);
  ivec2 size = textureSize(uPosition, 0);
  int set = (px.y % uTile) * uTile + px.x % uTile;
  int base = (slot * uTile * uTile + set) * uSamples;
  float footprint = uCameraOrthographic != 0 ? uPixelScale : uPixelScale * length(xo - uCameraPosition);
  vec3 sum = vec3(0.0), coverage = vec3(0.0);
  for (int j = 0; j < uSamples; ++j) {
    IsPatternGpu e = pattern[base + j];
    vec3 pp = xo + (e.offsetWeight.x * t1 + e.offsetWeight.y * t2) / IS_MM_PER_M;  // p'_j [m]
    vec4 clip = uViewProjection * vec4(pp, 1.0);
    if (!(clip.w > 0.0)) continue;
    vec2 pixel = (clip.xy / clip.w * 0.5 + 0.5) * vec2(size);
    if (any(lessThan(pixel, vec2(0.0))) || any(greaterThanEqual(pixel, vec2(size)))) continue;
    ivec2 q = ivec2(pixel);
    vec4 hit = texelFetch(uPosition, q, 0);
    if (int(hit.w + 0.5) != slot + 1) continue;  // another object, an opaque one or nothing
    vec3 nq = normalize(texelFetch(uNormal, q, 0).xyz);
    vec3 ray = isViewRay(pp, uCameraPosition, uCameraForward, uCameraOrthographic);
    vec3 p = sssPointOnTexel(pp, ray, hit.xyz, nq, 1);
    float rPrime = length(e.offsetWeight.xy) / IS_MM_PER_M;
    if (length(p - pp) > uDepthRatio * max(rPrime, footprint)) continue;  // across a depth discontinuity
    coverage += e.coverage.rgb;
    float r = length(p - xo) * IS_MM_PER_M;
    float jacobian =
        uJacobian != 0 ? isAreaRatio(pp, no, p, nq, uCameraPosition, uCameraForward, uCameraOrthographic) : 1.0;
    vec3 rd = vec3(standardDipoleRd(r, k0).sd, standardDipoleRd(r, k1).sd, standardDipoleRd(r, k2).sd);
    sum += rd * texelFetch(uIrradiance, q, 0).rgb * (jacobian * e.offsetWeight.z);
  }
  oSum = vec4(sum, 1.0);
  oCoverage = vec4(coverage, 1.0);
}
