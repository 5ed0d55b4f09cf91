#version 450 core
// The candle's flame: a teardrop of half-width w(v) = halfWidth f(v) / f(1/3), f(v) = √v (1 − v),
// widest a third of the way up; across each row the profile 3/2 (1 − x²) (mean 1 over x ∈ [−1, 1]),
// brighter towards the base by 1.3 − 0.6 v. uRadiance is the light's intensity over the integral
// of that profile over the teardrop (FlameShape::effectiveArea), so the flame drawn sends the camera
// the point light's intensity.
uniform vec3 uRadiance;

in vec2 vUv;
layout(location = 0) out vec4 oRadiance;
layout(location = 1) out vec4 oCoverage;

float flameWidth(float v) {
  const float widest = 0.38490018;  // f(1/3) = √(1/3) · 2/3
  return sqrt(max(v, 0.0)) * (1.0 - v) / widest;
}

void main() {
  float w = flameWidth(vUv.y);
  float x = w > 0.0 ? vUv.x / w : 2.0;
  if (abs(x) >= 1.0) discard;
  oRadiance = vec4(uRadiance * (1.5 * (1.0 - x * x)) * (1.3 - 0.6 * vUv.y), 0.0);
  // Multiplied into the coverage (FlamePass's blend): r, g, b kept, alpha halved, so that the wax's
  // pixels with the flame in front of them are told apart (Renderer::translucentMask).
  oCoverage = vec4(1.0, 1.0, 1.0, 0.5);
}
