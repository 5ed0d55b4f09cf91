#version 450 core
// Lambertian reflection of every light (with shadows) and of a uniform ambient sky:
// L = ρ/π · E + ρ · L_ambient, in linear radiance.
#include "common/lights.glsl"

in vec3 vWorldPosition;
in vec3 vWorldNormal;

uniform vec3 uAlbedo;
uniform vec3 uAmbient;
uniform vec3 uCameraPosition;
uniform int uCameraOrthographic;
uniform vec3 uCameraForward;

layout(location = 0) out vec4 oRadiance;

const float PI = 3.14159265358979;

void main() {
  vec3 n = normalize(vWorldNormal);
  // Open meshes (the bunny has holes) show their inside: shade the side facing the camera.
  vec3 toCamera = uCameraOrthographic != 0 ? -uCameraForward : uCameraPosition - vWorldPosition;
  if (dot(n, toCamera) < 0.0) n = -n;
  vec3 e = lightIrradiance(vWorldPosition, n);
  oRadiance = vec4(uAlbedo / PI * e + uAlbedo * uAmbient, 1.0);
}
