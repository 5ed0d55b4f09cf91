#version 450 core
// The candle's flame (sss/flame_pass.h): a sheet standing on the wick, turned about the candle's
// axis to face the camera, in rows (a triangle strip of 2 × rows vertices from gl_VertexID) so that
// the sway bends it: height v sits at base + v·height·up + v²·sway. Across: x ∈ [−reach, reach]
// half-widths, wide enough for the soft edge (shaders/flame/flame_profile.glsl); up: v ∈ [0, tip reach].
#include "flame/flame_profile.glsl"

uniform vec3 uBase;        // world: the flame's base on the axis
uniform vec3 uUp;          // world: the candle's axis, unit
uniform float uHeight;     // world units
uniform float uHalfWidth;  // world units, at the widest
uniform vec3 uSway;        // world: where the sway moves the tip (v = 1)
uniform mat4 uViewProjection;
uniform vec3 uCameraPosition;
uniform vec3 uCameraForward;
uniform int uCameraOrthographic;

const int kRows = 12;  // sss/flame_pass.cpp kFlameRows

out vec2 vUv;  // x across in half-widths, v up

void main() {
  int row = gl_VertexID / 2;
  float v = FLAME_TIP_REACH * float(row) / float(kRows - 1);
  float x = (gl_VertexID & 1) == 0 ? -FLAME_EDGE_REACH : FLAME_EDGE_REACH;
  vec3 centre = uBase + 0.4 * uHeight * uUp;
  vec3 toCamera = uCameraOrthographic != 0 ? -uCameraForward : normalize(uCameraPosition - centre);
  vec3 side = cross(uUp, toCamera);
  // Seen along the axis the flame is a point: any side will do.
  side = dot(side, side) > 1e-8 ? normalize(side) : normalize(cross(uUp, abs(uUp.x) < 0.9 ? vec3(1, 0, 0) : vec3(0, 1, 0)));
  vUv = vec2(x, v);
  vec3 p = uBase + v * uHeight * uUp + v * v * uSway + x * uHalfWidth * side;
  gl_Position = uViewProjection * vec4(p, 1.0);
}
