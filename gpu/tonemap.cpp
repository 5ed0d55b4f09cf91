#include "gpu/tonemap.h"

#include <cmath>
#include <stdexcept>

#include "gpu/glsl_shared.h"

namespace tallow::glsl {
#include "shaders/common/tonemap.glsl"
}  // namespace tallow::glsl

namespace tallow::gpu {

glm::vec3 toneMapToSrgb(const glm::vec3& radiance, const ToneMapSettings& settings) {
  return glsl::toneMapToSrgb(radiance, std::exp2(settings.exposureEv), static_cast<int>(settings.op));
}

glm::vec3 toneMapLinear(const glm::vec3& radiance, const ToneMapSettings& settings) {
  return glsl::toneMapLinear(radiance, std::exp2(settings.exposureEv), static_cast<int>(settings.op));
}

float srgbEncode(float linear) { return glsl::srgbEncode(linear); }

float ditherLevels(int x, int y) { return glsl::ditherLevels(x, y); }

float quantize8(float encoded, float dither) { return glsl::quantize8(encoded, dither); }

ToneMap parseToneMap(std::string_view name) {
  if (name == "clamp") return ToneMap::Clamp;
  if (name == "reinhard") return ToneMap::Reinhard;
  if (name == "aces") return ToneMap::Aces;
  if (name == "hue-preserving") return ToneMap::HuePreserving;
  throw std::invalid_argument("unknown tone map \"" + std::string(name) + "\" (clamp, reinhard, aces, hue-preserving)");
}

std::string_view toneMapName(ToneMap op) {
  switch (op) {
    case ToneMap::Clamp: return "clamp";
    case ToneMap::Reinhard: return "reinhard";
    case ToneMap::Aces: return "aces";
    case ToneMap::HuePreserving: return "hue-preserving";
  }
  return "?";
}

}  // namespace tallow::gpu
