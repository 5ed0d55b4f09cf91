#version 450 core
// Step 1 of the paper (Fig. 3): the light's G-buffer, world position and normal of the first
// surface the light meets, with the translucent surface's tag (slot + 1, the liquid's slot on a
// candle's pool: materials/slots.glsl; 0 for opaque occluders, whose texels lend no samples: the
// translucent surface behind them is in shadow).
#include "materials/slots.glsl"

in vec3 vWorldPosition;
in vec3 vWorldNormal;

uniform int uSlot;  // the object's main slot, −1 for an opaque one

layout(location = 0) out vec4 oPosition;  // xyz: world position [m], w: tag
layout(location = 1) out vec4 oNormal;    // xyz: unit normal

void main() {
  oPosition = vec4(vWorldPosition, float(surfaceSlot(uSlot, vWorldPosition, vWorldNormal) + 1));
  oNormal = vec4(normalize(vWorldNormal), 0.0);
}
