#version 450 core
// The candle's flame (sss/flame_pass.h): a quad standing on the wick, turned about the candle's
// axis to face the camera. Corners from gl_VertexID (a triangle strip of 4): u ∈ [−1, 1] across,
// v ∈ [0, 1] up.
uniform vec3 uBase;        // world: the flame's base on the axis
uniform vec3 uUp;          // world: the candle's axis, unit
uniform float uHeight;     // world units
uniform float uHalfWidth;  // world units
uniform mat4 uViewProjection;
uniform vec3 uCameraPosition;
uniform vec3 uCameraForward;
uniform int uCameraOrthographic;

out vec2 vUv;

void main() {
  vec2 uv = vec2((gl_VertexID & 1) == 0 ? -1.0 : 1.0, (gl_VertexID & 2) == 0 ? 0.0 : 1.0);
  vec3 centre = uBase + 0.5 * uHeight * uUp;
  vec3 toCamera = uCameraOrthographic != 0 ? -uCameraForward : normalize(uCameraPosition - centre);
  vec3 side = cross(uUp, toCamera);
  // Seen along the axis the flame is a point: any side will do.
  side = dot(side, side) > 1e-8 ? normalize(side) : normalize(cross(uUp, abs(uUp.x) < 0.9 ? vec3(1, 0, 0) : vec3(0, 1, 0)));
  vUv = uv;
  gl_Position = uViewProjection * vec4(uBase + uv.x * uHalfWidth * side + uv.y * uHeight * uUp, 1.0);
}
