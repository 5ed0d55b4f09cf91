#pragma once
// What a pass may declare that it reads, besides other passes' outputs: the named inputs of a
// frame and a fingerprint of each one's current value. A pass reruns when the fingerprint of
// something it declared changed since it last ran (sss/pass.h); nothing else decides what is stale.
//
// The names are
//   - every registry key that reaches RenderSettings ("sss.maps", "render.width", …, the same
//     strings as app/config/params.cpp: tests/frame_invalidation_gltest.cpp checks that each
//     registry key has its input and that setting the key changes exactly that input);
//   - the scene, in parts: "scene.shapes" (shapes, sizes, transforms, which are translucent),
//     "scene.albedo", "scene.materials" (coefficients and heterogeneous volumes),
//     "scene.light_placement" (kinds, directions, positions, which cast shadows),
//     "scene.light_intensity", "scene.camera", "scene.environment" (the map's file, rotation and
//     scale), "scene.ambient", "scene.background", "scene.map_directions";
//   - "time", the animation time (only the passes of moving fields declare it), and
//     "accumulation", the count of Renderer::restartAccumulation calls.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "sss/render_settings.h"
#include "sss/scene.h"

namespace tallow::sss {

/// One frame's inputs: the scene at its time (lights moved with their flames), the settings.
struct FrameState {
  const Scene& scene;
  const RenderSettings& settings;
  double timeS = 0.0;
  int accumulation = 0;  ///< Renderer::restartAccumulation calls so far
};

/// A 64-bit fingerprint of `name`'s value in `state` (FNV-1a over the value's bytes: floats by their
/// bits, so any change of any input changes it). Throws std::logic_error for an unknown name.
std::uint64_t inputFingerprint(std::string_view name, const FrameState& state);
/// Every input name, settings keys first, in a fixed order.
const std::vector<std::string>& inputNames();
bool isInput(std::string_view name);
/// Inputs that only the display reads (tone map, exposure): no pass declares them, and changing
/// one reruns nothing.
bool isDisplayOnlyInput(std::string_view name);

/// Accumulates values into an FNV-1a 64-bit fingerprint.
class Fingerprint {
 public:
  Fingerprint& bytes(const void* data, std::size_t n);
  template <typename T>
  Fingerprint& operator<<(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    return bytes(&v, sizeof v);
  }
  Fingerprint& operator<<(const std::string& s) { return bytes(s.data(), s.size()) << s.size(); }
  std::uint64_t value() const { return h_; }

 private:
  std::uint64_t h_ = 14695981039346656037ull;
};

}  // namespace tallow::sss
