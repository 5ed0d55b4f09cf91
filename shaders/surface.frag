#version 450 core
// Opaque surfaces: Lambertian reflection of every light (with shadows) and of a uniform ambient
// sky, L = ρ/π · E + ρ · L_ambient. Translucent surfaces with radiosity maps (uTranslucent):
// L = F_t(ω_o)/π · B (Eq. 5, B from Algorithm 1) + F_r(ω_o) · L_ambient (the sky seen in the
// surface's specular reflection, Fresnel-weighted).
#include "common/lights.glsl"
#include "bssrdf/fresnel.glsl"
#include "sss/algorithm1.glsl"

in vec3 vWorldPosition;
in vec3 vWorldNormal;

uniform vec3 uAlbedo;
uniform vec3 uAmbient;
uniform vec3 uCameraPosition;
uniform int uCameraOrthographic;
uniform vec3 uCameraForward;
uniform int uTranslucent;  // 1: shaded from the scattered radiosity maps
uniform float uEta;        // its relative index of refraction

layout(location = 0) out vec4 oRadiance;
layout(location = 1) out vec4 oCoverage;  // r: shaded from the radiosity maps, g: some map sees it

const float PI = 3.14159265358979;

void main() {
  vec3 n = normalize(vWorldNormal);
  vec3 dpdx = dFdx(vWorldPosition), dpdy = dFdy(vWorldPosition);  // uniform control flow here
  // Open meshes (the bunny has holes) show their inside: shade the side facing the camera.
  vec3 toCamera = uCameraOrthographic != 0 ? -uCameraForward : uCameraPosition - vWorldPosition;
  bool backFacing = dot(n, toCamera) < 0.0;
  if (uTranslucent != 0) {
    float seenBy;
    vec3 b = scatteredRadiosity(vWorldPosition, backFacing ? -n : n, dpdx, dpdy, seenBy);
    float cosO = clamp(abs(dot(n, normalize(toCamera))), 0.0, 1.0);
    oRadiance = vec4(fresnelTransmittance(cosO, uEta) / PI * b + fresnelReflectance(cosO, uEta) * uAmbient, 1.0);
    oCoverage = vec4(1.0, seenBy > 0.0 ? 1.0 : 0.0, 0.0, 1.0);
    return;
  }
  if (backFacing) n = -n;
  vec3 e = lightIrradiance(vWorldPosition, n);
  oRadiance = vec4(uAlbedo / PI * e + uAlbedo * uAmbient, 1.0);
  oCoverage = vec4(0.0);
}
