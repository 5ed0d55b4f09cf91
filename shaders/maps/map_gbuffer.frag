#version 450 core
// The maps' G-buffer for the compute gather: x_o and n_o of each visible map texel, exactly the
// values the fragment gather sees (same rasterisation, same interpolation), with the surface's
// slot + 1 (materials/slots.glsl: the liquid's on a candle's pool).
#include "materials/slots.glsl"

in vec3 vWorldPosition;
in vec3 vWorldNormal;

uniform int uSlot;

layout(location = 0) out vec4 oPosition;
layout(location = 1) out vec4 oNormal;

void main() {
  oPosition = vec4(vWorldPosition, float(surfaceSlot(uSlot, vWorldPosition, vWorldNormal) + 1));
  oNormal = vec4(vWorldNormal, 0.0);
}
