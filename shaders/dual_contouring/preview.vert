#version 450 core
// Minimal Lambertian preview of the extracted mesh (tests and debugging): the layout draw() feeds.
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
uniform mat4 uViewProjection;
out vec3 vNormal;
void main() {
  vNormal = aNormal;
  gl_Position = uViewProjection * vec4(aPosition, 1.0);
}
