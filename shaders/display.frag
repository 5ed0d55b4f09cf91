#version 450 core
// Linear radiance → display sRGB, with the same tone map the PNG writer uses.
#include "common/tonemap.glsl"

in vec2 vUv;
uniform sampler2D uRadiance;
uniform float uExposureScale;
uniform int uToneMap;

layout(location = 0) out vec4 oColor;

void main() {
  vec3 radiance = texture(uRadiance, vUv).rgb;
  oColor = vec4(toneMapToSrgb(radiance, uExposureScale, uToneMap), 1.0);
}
