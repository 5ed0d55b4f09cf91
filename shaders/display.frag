#version 450 core
// Linear radiance → display sRGB, with the same tone map the PNG writer uses.
#include "common/tonemap.glsl"

in vec2 vUv;
uniform sampler2D uRadiance;
uniform float uExposureScale;
uniform int uToneMap;
uniform int uDither;  // 1: 8-bit levels, dithered; 0: the encoded values (a float target)

layout(location = 0) out vec4 oColor;

void main() {
  vec3 radiance = texture(uRadiance, vUv).rgb;
  vec3 srgb = toneMapToSrgb(radiance, uExposureScale, uToneMap);
  if (uDither == 0) {
    oColor = vec4(srgb, 1.0);
    return;
  }
  // The window's 8-bit levels, dithered as the PNG writer's (common/tonemap.glsl): k / 255 is
  // stored exactly as level k.
  float d = ditherLevels(int(gl_FragCoord.x), int(gl_FragCoord.y));
  oColor = vec4(quantize8(srgb.x, d), quantize8(srgb.y, d), quantize8(srgb.z, d), 255.0) / 255.0;
}
