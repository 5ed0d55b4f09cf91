#pragma once
// Tone mapping for PNG output: the C++ face of shaders/common/tonemap.glsl.
#include <glm/glm.hpp>

#include <string>
#include <string_view>

namespace tallow::gpu {

enum class ToneMap { Clamp = 0, Reinhard = 1, Aces = 2, HuePreserving = 3 };

/// Whether 8-bit output adds the triangular dither of shaders/common/tonemap.glsl before rounding
/// (the window, PNGs, videos): On for pictures; Off rounds, round(v × 255) (tests of the rounding
/// itself, and the display pass drawn into a float target).
enum class Dither { Off, On };

struct ToneMapSettings {
  ToneMap op = ToneMap::Aces;
  float exposureEv = 0.0f;  ///< stops; the linear scale is 2^ev
};

/// Linear radiance → display sRGB in [0, 1], exactly as the display shader computes it.
glm::vec3 toneMapToSrgb(const glm::vec3& radiance, const ToneMapSettings& settings);
/// The same before the sRGB transfer function: linear display values in [0, 1].
glm::vec3 toneMapLinear(const glm::vec3& radiance, const ToneMapSettings& settings);
/// The sRGB transfer function alone (IEC 61966-2-1).
float srgbEncode(float linear);
/// The 8-bit outputs' dither at pixel (x, y), in levels on (−1, 1), triangular (tonemap.glsl).
float ditherLevels(int x, int y);
/// An encoded value → its 8-bit level, dithered by `dither` levels; 0 and 1 (and NaN → 0) exact.
float quantize8(float encoded, float dither);

/// "clamp" | "reinhard" | "aces" | "hue-preserving"; throws std::invalid_argument otherwise.
ToneMap parseToneMap(std::string_view name);
std::string_view toneMapName(ToneMap op);

}  // namespace tallow::gpu
