#version 450 core
// Depth of opaque and translucent geometry as seen from a light: the rasterised depth is what the
// receivers compare (point lights: common/cube_shadow_depth.glsl), so the program has no fragment
// shader and the pass keeps early depth.
layout(location = 0) in vec3 aPosition;

uniform mat4 uModel;
uniform mat4 uLightViewProjection;  // point lights: rotation and projection only, about the light
uniform vec3 uLightOrigin;          // point lights: the light's position; directional: 0

void main() {
  // A point light's offset is taken before the projection, as the receivers take theirs: a view
  // matrix's translation (about 1 m) folded into a float projection costs ~1e-7 m of the offset
  // (~6e-8 m ulp), 2e-6 of depth for a 5 cm range — more than one texel of normal offset moves it.
  vec4 world = uModel * vec4(aPosition, 1.0);
  gl_Position = uLightViewProjection * vec4(world.xyz - uLightOrigin, 1.0);
}
