#version 450 core
// Layered passes of the radiosity maps (light G-buffers, map depth, map shading): world position
// and normal; the instance picks the layer in layered.geom.
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;

uniform mat4 uModel;
uniform mat3 uNormalMatrix;

out vec3 vgPosition;
out vec3 vgNormal;
flat out int vgInstance;

void main() {
  vec4 world = uModel * vec4(aPosition, 1.0);
  vgPosition = world.xyz;
  vgNormal = uNormalMatrix * aNormal;
  vgInstance = gl_InstanceID;
  gl_Position = world;
}
