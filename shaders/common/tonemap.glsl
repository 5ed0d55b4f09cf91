// Tone mapping and the sRGB transfer function, shared by the display pass (GLSL) and the PNG
// writer (C++), so that a saved PNG shows exactly what the window shows.
#include "common/shared.glsl"

const int TONEMAP_CLAMP = 0;     // exposure, then clip to [0, 1]
const int TONEMAP_REINHARD = 1;  // c / (1 + c) per channel (Reinhard et al. 2002, Eq. 3)
const int TONEMAP_ACES = 2;      // Narkowicz's 2015 fit of the ACES filmic curve

TALLOW_FN float srgbEncode(float linear) {
  // IEC 61966-2-1 sRGB opto-electronic transfer function.
  float c = clamp(linear, 0.0f, 1.0f);
  return c <= 0.0031308f ? 12.92f * c : 1.055f * pow(c, 1.0f / 2.4f) - 0.055f;
}

TALLOW_FN vec3 toneMapLinear(vec3 radiance, float exposureScale, int op) {
  vec3 c = max(radiance * exposureScale, vec3(0.0f));
  if (op == TONEMAP_REINHARD) {
    c = c / (vec3(1.0f) + c);
  } else if (op == TONEMAP_ACES) {
    c = (c * (2.51f * c + vec3(0.03f))) / (c * (2.43f * c + vec3(0.59f)) + vec3(0.14f));
  }
  return clamp(c, vec3(0.0f), vec3(1.0f));
}

TALLOW_FN vec3 toneMapToSrgb(vec3 radiance, float exposureScale, int op) {
  vec3 c = toneMapLinear(radiance, exposureScale, op);
  return vec3(srgbEncode(c.x), srgbEncode(c.y), srgbEncode(c.z));
}
