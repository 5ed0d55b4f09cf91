#version 450 core
// Lambertian shading under a fixed direction; alpha carries coverage for tests.
in vec3 vNormal;
out vec4 fragColor;
void main() {
  float lambert = max(dot(normalize(vNormal), normalize(vec3(0.3, 0.8, 0.5))), 0.0);
  fragColor = vec4(vec3(0.1 + 0.9 * lambert), 1.0);
}
