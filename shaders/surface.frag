#version 450 core
// The camera pass. Opaque surfaces: Lambertian reflection of every light (with shadows), of the
// light the frame's method carries to the surroundings (surroundingsIrradiance: the VPLs' emergent light,
// Eq. 15, where a method sums it here; the radiosity maps add it after the pass in compute from the
// receivers' point, normal and albedo this pass leaves, maps/vpl_receivers.comp) and of a uniform
// ambient sky, L = ρ/π · (E + E_vpl) + ρ · L_ambient. Translucent surfaces (uTranslucent):
// L = F_t(ω_o)/π · B (Eq. 5) + F_r(ω_o) · L_env(mirror direction): the specular reflection,
// Fresnel-weighted, of the environment map, or of the uniform ambient sky when there is none
// (render.specular off: no reflection), and of the candles' flames (flame/flame_mirror.glsl: the
// melt pool's flat surface shows the flame). A candle's pool has its own material
// (materials/slots.glsl): its η here, its BSSRDF in the gather. The frame's method gives B: each
// method has its own variant of this pass, which includes the method's file as
// TALLOW_SURFACE_METHOD (camera/surface_method.glsl: Algorithm 1 over the radiosity maps, the
// gather per pixel, the image-space accumulation, SSLPV's Eq. 7), so a variant holds and binds
// only its method's code and samplers.
#include "common/lights.glsl"
#include "bssrdf/fresnel.glsl"
#include "materials/slots.glsl"
#include "flame/flame_mirror.glsl"
#include "common/octahedral.glsl"
#include TALLOW_SURFACE_METHOD

// Depth test before shading: fragments behind what is already drawn cost no shading.
layout(early_fragment_tests) in;

in vec3 vWorldPosition;
in vec3 vWorldNormal;

uniform vec3 uAlbedo;
uniform vec3 uAmbient;
uniform vec3 uCameraPosition;
uniform int uCameraOrthographic;
uniform vec3 uCameraForward;
uniform int uTranslucent;  // 1: this object is shaded by the frame's method
uniform int uSlot;         // this object's main translucent slot (materials/slots.glsl), −1: none
uniform int uSpecular;     // render.specular
uniform int uEnvironment;  // 1: uEnvMap holds the scene's environment
uniform sampler2D uEnvMap; // lat-long radiance (sss/maps/environment_lights.h conventions)
uniform float uEnvRotation;  // radians about +y, counter-clockwise seen from above
uniform float uEnvScale;
// The flames (sss::FlameSheet, as drawn): a mirror-like translucent surface reflects them.
const int MAX_FLAMES = 8;
uniform int uFlameCount;
uniform vec3 uFlameBase[MAX_FLAMES];
uniform vec3 uFlameUp[MAX_FLAMES];
uniform vec3 uFlameSway[MAX_FLAMES];
uniform vec3 uFlameSize[MAX_FLAMES];  // height, widest half-width, radiance per unit of flameProfile
// Each flame's point light (index into common/lights.glsl's point lights, −1: none): the mirror shows
// the flame only where its light's shadow map sees x_o (the pool, not the puddle behind the wax).
uniform int uFlamePointLight[MAX_FLAMES];

layout(location = 0) out vec4 oRadiance;
layout(location = 1) out vec4 oCoverage;  // r: shaded from the radiosity maps, g: some map sees it, b: opaque
// sss.maps=auto's per-pixel record, counted after the pass (maps/coverage_histogram.comp): the bins
// + 1 of Algorithm 1's first map and second facing map (0: not shaded by Algorithm 1).
layout(location = 2) out uvec2 oCoverageBins;
// The translucent part of oRadiance, F_t/π·B (a: 1 on a translucent surface, 0 elsewhere): a still
// weights it by the samples the estimate holds and the rest equally (camera/still_average.comp).
layout(location = 3) out vec4 oTranslucent;
// An opaque pixel's point (xyz: its float bits) and normal (w: packOctahedral's bits), in an
// integer target so that no bit is changed on the way, and its albedo (a: 1), for the passes that
// light the receivers after this one; a = 0 elsewhere.
layout(location = 4) out uvec4 oReceiver;
layout(location = 5) out vec4 oReceiverAlbedo;

const float PI = 3.14159265358979;

// Radiance arriving from direction d (unit, from the scene outward). The inverse of
// environmentDirection (sss/maps/environment_lights.h): turn back by the rotation, then
// θ = acos(d.y), φ = atan2(d.x, −d.z), u = φ/2π + 1/2, v = θ/π.
vec3 environmentRadiance(vec3 d) {
  float c = cos(uEnvRotation), s = sin(uEnvRotation);
  vec3 r = vec3(c * d.x - s * d.z, d.y, s * d.x + c * d.z);
  float theta = acos(clamp(r.y, -1.0, 1.0));
  float phi = atan(r.x, -r.z);
  return uEnvScale * textureLod(uEnvMap, vec2(phi / (2.0 * PI) + 0.5, theta / PI), 0.0).rgb;
}

void main() {
  vec3 n = normalize(vWorldNormal);
  vec3 dpdx = dFdx(vWorldPosition), dpdy = dFdy(vWorldPosition);  // uniform control flow here
  // Open meshes (the bunny has holes) show their inside: shade the side facing the camera.
  vec3 toCamera = uCameraOrthographic != 0 ? -uCameraForward : uCameraPosition - vWorldPosition;
  bool backFacing = dot(n, toCamera) < 0.0;
  if (uTranslucent != 0) {
    vec3 facing = backFacing ? -n : n;
    int slot = surfaceSlot(uSlot, vWorldPosition, n);
    float eta = uSlotEta[slot];  // a translucent object always has a slot
    TranslucentShading shading = translucentShading(vWorldPosition, facing, dpdx, dpdy, slot);
    oCoverageBins = shading.coverageBins;
    vec3 v = normalize(toCamera);
    float cosO = clamp(dot(facing, v), 0.0, 1.0);
    vec3 mirror = reflect(-v, facing);
    vec3 mirrored = uEnvironment != 0 ? environmentRadiance(mirror) : uAmbient;
    for (int f = 0; f < uFlameCount; ++f) {
      vec3 seen = flameSeenAlong(vWorldPosition, mirror, uFlameBase[f], uFlameUp[f], uFlameSize[f].x, uFlameSize[f].y,
                                 uFlameSway[f]);
      if (seen != vec3(0.0) && uFlamePointLight[f] >= 0) seen *= pointVisibility(uFlamePointLight[f], vWorldPosition, facing);
      mirrored += uFlameSize[f].z * seen;
    }
    vec3 specular = uSpecular != 0 ? fresnelReflectance(cosO, eta) * mirrored : vec3(0.0);
    vec3 transmitted = fresnelTransmittance(cosO, eta) / PI * shading.b;
    oRadiance = vec4(transmitted + specular, 1.0);
    oTranslucent = vec4(transmitted, 1.0);
    oCoverage = vec4(1.0, shading.seenBy > 0.0 ? 1.0 : 0.0, 0.0, 1.0);
    oReceiver = uvec4(0u);
    oReceiverAlbedo = vec4(0.0);
    return;
  }
  if (backFacing) n = -n;
  vec3 e = lightIrradiance(vWorldPosition, n) + surroundingsIrradiance(vWorldPosition, n);
  oRadiance = vec4(uAlbedo / PI * e + uAlbedo * uAmbient, 1.0);
  oCoverage = vec4(0.0, 0.0, 1.0, 0.0);
  oCoverageBins = uvec2(0u);
  oTranslucent = vec4(0.0);
  oReceiver = uvec4(floatBitsToUint(vWorldPosition), packOctahedral(n));
  oReceiverAlbedo = vec4(uAlbedo, 1.0);
}
