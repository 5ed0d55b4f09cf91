#version 450 core
// Step 2 of the paper (Fig. 3), as the paper does it: the translucent objects rasterised into the K
// maps (layered), the gather (gather.glsl) once per visible texel after a depth pre-pass.
// Blended additively: the map holds Σ over the F accumulated frames of B_N (Algorithm 1 divides).
#include "maps/gather.glsl"

in vec3 vWorldPosition;
in vec3 vWorldNormal;
flat in int vLayer;

uniform int uSlot;  // this object's main translucent slot

layout(location = 0) out vec4 oRadiosity;  // rgb: B_N [W/m²], a: 1 (counts frames)

void main() {
  vec3 n = normalize(vWorldNormal);
  vec3 b = gatherScatteredRadiosity(vWorldPosition, n, uvec2(gl_FragCoord.xy), vLayer, surfaceSlot(uSlot, vWorldPosition, n));
  oRadiosity = vec4(b, 1.0);
}
