#version 450 core
// The maps' G-buffer for the compute gather: x_o and n_o of each visible map texel, exactly the
// values the fragment gather sees (same rasterisation, same interpolation), with slot + 1.
in vec3 vWorldPosition;
in vec3 vWorldNormal;

uniform int uSlot;

layout(location = 0) out vec4 oPosition;
layout(location = 1) out vec4 oNormal;

void main() {
  oPosition = vec4(vWorldPosition, float(uSlot + 1));
  oNormal = vec4(vWorldNormal, 0.0);
}
