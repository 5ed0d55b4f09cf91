// What both of method=burley's kernels share (scatter.comp: discs; separable.comp: two 1D passes):
// the G-buffer, the slots' materials, a pixel's world size, and the light through thin parts —
// per light behind x_o, E_back · F_t · T(t) with t the thickness between x_o and the first surface
// the light's shadow map sees (profile.glsl's transmittance).
#include "common/lights.glsl"
#include "bssrdf/real.glsl"
#include "bssrdf/fresnel.glsl"
#include "peers/burley/profile.glsl"

const int BURLEY_MAX_SLOTS = 8;
uniform vec3 uSigmaA[BURLEY_MAX_SLOTS];
uniform vec3 uSigmaS[BURLEY_MAX_SLOTS];
uniform vec3 uG[BURLEY_MAX_SLOTS];
uniform float uEta[BURLEY_MAX_SLOTS];
uniform sampler2D uPosition;  // burley.gbuffer: world position, slot + 1
uniform sampler2D uNormal;
uniform sampler2DArray uDirShadowDepth;  // the shadow maps as depths (compare mode off)
uniform samplerCubeArray uPointShadowDepth;
uniform vec3 uCameraPosition;
uniform int uCameraOrthographic;
uniform float uPixelScale;  // a pixel's world size: per metre of distance (perspective) or in metres
uniform int uTransmission;

const float BURLEY_MM_PER_M = 1000.0;

// A and d of band c of a slot's material.
BurleyBand slotBand(int slot, int c) {
  return burleyBand(bssrdfCoefficients(uSigmaA[slot][c], uSigmaS[slot][c], uG[slot][c], uEta[slot]));
}

// Metres per pixel at world point p.
float pixelFootprint(vec3 p) {
  return uCameraOrthographic != 0 ? uPixelScale : uPixelScale * length(p - uCameraPosition);
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

