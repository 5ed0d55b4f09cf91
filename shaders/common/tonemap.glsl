// Tone mapping and the sRGB transfer function, shared by the display pass (GLSL) and the PNG
// writer (C++), so that a saved PNG shows exactly what the window shows.
#include "common/shared.glsl"

const int TONEMAP_CLAMP = 0;     // exposure, then clip to [0, 1]
const int TONEMAP_REINHARD = 1;  // c / (1 + c) per channel (Reinhard et al. 2002, Eq. 3)
const int TONEMAP_ACES = 2;      // Narkowicz's 2015 fit of the ACES filmic curve
const int TONEMAP_HUE_PRESERVING = 3;  // luminance sigmoid, then a path to white at constant hue

// The hue-preserving operator (render.tonemap=hue-preserving). As in AgX (Sobotka's display
// transform for Blender), exposure is compressed by a sigmoid of log luminance and very bright
// colours run to white instead of clipping channel by channel; unlike the per-channel curves above,
// it acts on luminance alone, so a saturated colour keeps its hue as it brightens.
//  1. Luminance Y = 0.2126 R + 0.7152 G + 0.0722 B (ITU-R BT.709, the primaries of sRGB).
//  2. Display luminance Y_d = Yⁿ / (Yⁿ + kⁿ) = 1 / (1 + e^(−n (ln Y − ln k))): the logistic function
//     of ln Y, 0 at black, strictly increasing, → 1 as Y → ∞; n sets the contrast (the slope in
//     log exposure), and kⁿ = g^n (1/g − 1) maps scene mid grey g = 0.18 to display 0.18.
//  3. Colour: with r = c / Y, the colour at unit luminance (its BT.709-weighted mean is 1), the
//     output is Y_d (1 + s (r − 1)), the colour mixed with grey of the same luminance: its luminance
//     is Y_d for every s, and its hue angle is the input's, since scaling RGB by a positive factor
//     and adding grey leave the hue unchanged. s ∈ [0, 1] is the share of saturation kept. The
//     brightest channel is exactly 1 at s_max = (1/Y_d − 1) / (max r − 1); s = (1 + s_max^(−4))^(−1/4),
//     a smooth minimum of 1 and s_max, keeps the full colour while it fits well under 1 and then
//     fades it toward white (s_max → 0 as Y_d → 1), every channel staying below 1.
const float TONEMAP_HUE_CONTRAST = 1.5f;  // n
const float TONEMAP_HUE_GREY = 0.18f;     // g: scene mid grey, shown as display mid grey

TALLOW_FN vec3 toneMapHuePreserving(vec3 c) {
  float y = dot(c, vec3(0.2126f, 0.7152f, 0.0722f));
  if (!(y > 0.0f)) return vec3(0.0f);  // black (c ≥ 0: Y = 0 only when c = 0)
  // q = kⁿ Y^(−n), so Y_d = 1 / (1 + q) and 1/s_max = (max r − 1) Y_d / (1 − Y_d) = (max r − 1) / q;
  // written so that neither a huge nor a tiny Y overflows (Y ≥ 10⁻²⁰: q ≤ 10³⁰).
  float kn = pow(TONEMAP_HUE_GREY, TONEMAP_HUE_CONTRAST) * (1.0f / TONEMAP_HUE_GREY - 1.0f);
  float q = kn * pow(max(y, 1e-20f), -TONEMAP_HUE_CONTRAST);
  float displayY = 1.0f / (1.0f + q);
  vec3 r = c / y;
  float excess = min((max(max(r.x, r.y), r.z) - 1.0f) / max(q, 1e-30f), 1e8f);  // 1 / s_max
  float e2 = excess * excess;
  float keep = inversesqrt(sqrt(1.0f + e2 * e2));  // (1 + (1/s_max)⁴)^(−1/4)
  return displayY * (vec3(1.0f) + keep * (r - vec3(1.0f)));
}

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
  } else if (op == TONEMAP_HUE_PRESERVING) {
    c = toneMapHuePreserving(c);
  }
  return clamp(c, vec3(0.0f), vec3(1.0f));
}

TALLOW_FN vec3 toneMapToSrgb(vec3 radiance, float exposureScale, int op) {
  vec3 c = toneMapLinear(radiance, exposureScale, op);
  return vec3(srgbEncode(c.x), srgbEncode(c.y), srgbEncode(c.z));
}

// 8-bit output with dither (PNG, video, window). Rounding a smooth dark gradient to 8 bits draws
// rings of constant value one level apart, which the eye sees as bands (the candle's table glow).
// Adding noise of a triangular distribution on (−1, 1) levels before rounding makes the error of
// every output level independent of the signal, its mean zero and its variance constant (Lipshitz,
// Wannamaker and Vanderkooy 1992, "Quantization and dither: a theoretical survey", §5): a local
// mean of the bytes equals the signal, so no band remains. The noise is a fixed hash of the pixel
// (no flicker in a still). Within half a level of black or white there is no dither: black stays
// black and white white (what rounds to 0 or 255 is written so), at most half a level off there.
TALLOW_FN uint ditherHash(uint v) {
  // Wellons' "lowbias32" integer hash (2018): every output bit depends on every input bit.
  v = v ^ (v >> 16u);
  v = v * 0x7feb352du;
  v = v ^ (v >> 15u);
  v = v * 0x846ca68bu;
  return v ^ (v >> 16u);
}

/// The dither at pixel (x, y), in output levels: the sum of two uniforms on [0, 1) minus 1.
TALLOW_FN float ditherLevels(int x, int y) {
  uint h1 = ditherHash(uint(x) + 0x9e3779b9u * uint(y));
  uint h2 = ditherHash(h1 ^ 0x85ebca6bu);
  const float unit = 1.0f / 16777216.0f;  // 2^−24: the top 24 bits as a float in [0, 1)
  return float(h1 >> 8u) * unit + float(h2 >> 8u) * unit - 1.0f;
}

/// An encoded value in [0, 1] → its 8-bit level (0…255), dithered by `dither` levels.
TALLOW_FN float quantize8(float encoded, float dither) {
  float level = encoded * 255.0f;
  if (!(level >= 0.5f)) return 0.0f;  // NaN too
  if (level >= 254.5f) return 255.0f;
  return clamp(floor(level + 0.5f + dither), 0.0f, 255.0f);
}
