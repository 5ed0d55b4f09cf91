#version 450 core
// Overlay lines and points, dimmed where the camera's depth buffer shows something in front.
in vec4 vColor;

uniform int uPoints;
uniform vec3 uLineColor;
layout(binding = 0) uniform sampler2D uSceneDepth;  // the camera target's depth, same projection

layout(location = 0) out vec4 oColor;

// Depth units the overlay may lie behind the surface and still count as on it (lines of the
// surface itself, rasterised with another rule than its triangles).
const float DEPTH_SLACK = 2e-4;
const float LINE_ALPHA = 0.6;    // lines let the shading show through
const float HIDDEN_ALPHA = 0.15;

void main() {
  if (uPoints != 0) {
    vec2 p = 2.0 * gl_PointCoord - 1.0;
    float r2 = dot(p, p);
    if (r2 > 1.0) discard;
  }
  float scene = texelFetch(uSceneDepth, ivec2(gl_FragCoord.xy), 0).r;
  bool hidden = gl_FragCoord.z > scene + DEPTH_SLACK;
  vec3 c = uPoints != 0 ? vColor.rgb : uLineColor;
  float alpha = uPoints != 0 ? 1.0 : LINE_ALPHA;
  oColor = vec4(c, hidden ? HIDDEN_ALPHA : alpha);
}
