#version 450 core
// The candle's flame: its radiance at (x, v) from shaders/flame/flame_profile.glsl (the lines
// geometry::flameEmission integrates for the point light), scaled so that the flame's flux is the
// light's intensity (FollowedFlame::radianceScale). No hard edge: the profile fades to 0 itself.
#include "flame/flame_profile.glsl"

uniform float uRadianceScale;

in vec2 vUv;
layout(location = 0) out vec4 oRadiance;
layout(location = 1) out vec4 oCoverage;

void main() {
  vec3 radiance = flameProfile(vUv.x, vUv.y) * uRadianceScale;
  if (max(radiance.r, max(radiance.g, radiance.b)) <= 0.0) discard;
  oRadiance = vec4(radiance, 0.0);
  // Multiplied into the coverage (FlamePass's blend): r, g, b kept, alpha halved, so that the wax's
  // pixels with the flame in front of them are told apart (Renderer::translucentMask).
  oCoverage = vec4(1.0, 1.0, 1.0, 0.5);
}
