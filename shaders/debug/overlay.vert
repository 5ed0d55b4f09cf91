#version 450 core
// The view window's overlays (sss/debug_view_pass.h): triangles as lines (wireframe) or VPLs as
// points, over the final image.
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec4 aColor;  // points: rgb colour, a: point size in pixels

uniform mat4 uViewProjection;
uniform mat4 uModel;
uniform int uPoints;

out vec4 vColor;

void main() {
  gl_Position = uViewProjection * uModel * vec4(aPosition, 1.0);
  vColor = uPoints != 0 ? vec4(aColor.rgb, 1.0) : vec4(1.0);
  gl_PointSize = uPoints != 0 ? aColor.a : 1.0;
}
