#version 450 core
// Directional lights keep the rasterised depth; point lights store distance / range instead, so
// that all six cube faces share one comparison.
in vec3 vWorldPosition;

uniform int uStoreDistance;
uniform vec3 uLightPosition;
uniform float uRange;

void main() {
  if (uStoreDistance != 0) gl_FragDepth = length(vWorldPosition - uLightPosition) / uRange;
  else gl_FragDepth = gl_FragCoord.z;
}
