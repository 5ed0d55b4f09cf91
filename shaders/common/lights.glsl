// Light and shadow uniforms shared by the passes that shade opaque surfaces.
#include "common/cube_shadow_depth.glsl"

const int MAX_DIRECTIONAL_LIGHTS = 32;
const int MAX_POINT_LIGHTS = 8;

uniform int uDirCount;
uniform vec3 uDirDirection[MAX_DIRECTIONAL_LIGHTS];  // unit, toward the light
uniform vec3 uDirIrradiance[MAX_DIRECTIONAL_LIGHTS]; // W/m² on a surface facing the light
uniform int uDirShadowLayer[MAX_DIRECTIONAL_LIGHTS]; // layer in uDirShadow, −1 = no shadow
uniform mat4 uDirShadowMatrix[MAX_DIRECTIONAL_LIGHTS];  // world → [0,1]³ shadow-map coordinates
uniform float uDirShadowTexel[MAX_DIRECTIONAL_LIGHTS];  // world size of one shadow-map texel

uniform int uPointCount;
uniform vec3 uPointPosition[MAX_POINT_LIGHTS];
uniform vec3 uPointIntensity[MAX_POINT_LIGHTS];  // W/sr
uniform int uPointShadowLayer[MAX_POINT_LIGHTS]; // cube in uPointShadow, −1 = no shadow
uniform float uPointShadowRange[MAX_POINT_LIGHTS];  // far plane of the light's shadow cube
uniform float uPointShadowTexelAngle;               // angular size of one cube texel [rad]

uniform sampler2DArrayShadow uDirShadow;
uniform samplerCubeArrayShadow uPointShadow;
uniform float uShadowBias;  // extra offset along the normal, in shadow-map texels
uniform int uPcfRadius;

// How far the lookup point moves along the normal, in texels. A filter tap δ texels sideways
// (|δ| ≤ D = PCF radius + 1 for the bilinear comparison) sees the surface's own tangent plane
// nearer to the light by δ·tanθ; moving the point by b along the normal puts it b/cosθ nearer,
// so the point is never self-shadowed when b ≥ D·sinθ, i.e. for every angle when b ≥ D. The
// user's bias comes on top, against depth quantisation and curvature.
float normalOffsetTexels() { return float(uPcfRadius + 1) + uShadowBias; }

// Fraction of light reaching `p` from directional light i, filtered over (2r+1)² texels.
float directionalVisibility(int i, vec3 p, vec3 n) {
  int layer = uDirShadowLayer[i];
  if (layer < 0) return 1.0;
  // Normal offset against self-shadowing (acne), see normalOffsetTexels().
  vec3 q = p + n * (normalOffsetTexels() * uDirShadowTexel[i]);
  vec4 s = uDirShadowMatrix[i] * vec4(q, 1.0);
  s.z = min(s.z, 1.0);  // beyond the far plane: compare against the cleared depth (lit)
  vec2 texel = 1.0 / vec2(textureSize(uDirShadow, 0).xy);
  float sum = 0.0;
  float count = 0.0;
  for (int y = -uPcfRadius; y <= uPcfRadius; ++y)
    for (int x = -uPcfRadius; x <= uPcfRadius; ++x) {
      sum += texture(uDirShadow, vec4(s.xy + vec2(x, y) * texel, float(layer), s.z));
      count += 1.0;
    }
  return sum / count;
}

float pointVisibility(int i, vec3 p, vec3 n) {
  int layer = uPointShadowLayer[i];
  if (layer < 0) return 1.0;
  vec3 d = p - uPointPosition[i];
  float dist = length(d);
  vec3 q = p + n * (normalOffsetTexels() * uPointShadowTexelAngle * dist);
  vec3 dq = q - uPointPosition[i];
  return texture(uPointShadow, vec4(dq, float(layer)), cubeShadowDepth(dq, uPointShadowRange[i]));
}

// Irradiance at p with normal n from every light, shadows included [W/m²].
vec3 lightIrradiance(vec3 p, vec3 n) {
  vec3 e = vec3(0.0);
  for (int i = 0; i < uDirCount; ++i) {
    float c = dot(n, uDirDirection[i]);
    if (c > 0.0) e += uDirIrradiance[i] * c * directionalVisibility(i, p, n);
  }
  for (int i = 0; i < uPointCount; ++i) {
    vec3 l = uPointPosition[i] - p;
    float d2 = dot(l, l);
    float c = dot(n, l) * inversesqrt(d2);
    if (c > 0.0) e += uPointIntensity[i] * (c / d2) * pointVisibility(i, p, n);
  }
  return e;
}
