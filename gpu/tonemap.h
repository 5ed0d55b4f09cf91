#pragma once
// Tone mapping for PNG output: the C++ face of shaders/common/tonemap.glsl.
#include <glm/glm.hpp>

#include <string>
#include <string_view>

namespace tallow::gpu {

enum class ToneMap { Clamp = 0, Reinhard = 1, Aces = 2, HuePreserving = 3 };

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

/// "clamp" | "reinhard" | "aces" | "hue-preserving"; throws std::invalid_argument otherwise.
ToneMap parseToneMap(std::string_view name);
std::string_view toneMapName(ToneMap op);

}  // namespace tallow::gpu
