#pragma once
// What the view window shows instead of (or over) the final image: the intermediate results of
// the method, for inspection. The choice and its text form ("map:3", "gbuffer-normal:0:2") are
// plain data; sss/debug_view_pass.h draws them.
#include <string>
#include <string_view>
#include <vector>

namespace tallow::sss {

enum class DebugViewKind {
  Final,           ///< the tone-mapped image
  GBufferPosition, ///< a light's G-buffer: world positions (relative to the translucent bounds)
  GBufferNormal,   ///< a light's G-buffer: normals
  Map,             ///< one scattered radiosity map, B / π as radiance
  Coverage,        ///< Algorithm 1's coverage: translucent pixels seen / unseen by the maps, opaque
  Vpl,             ///< the final image with the VPLs drawn as points (size and colour: their light)
  Wireframe,       ///< the final image with the triangles drawn over it
  Difference,      ///< image − reference (red: brighter than the reference, blue: darker)
};

struct DebugView {
  DebugViewKind kind = DebugViewKind::Final;
  int light = 0;  ///< G-buffer views: index of the light in the scene
  int layer = 0;  ///< G-buffer views: cube face 0–5 of a point light; Map: the map k
  float exposureEv = 0.0f;  ///< extra exposure of the map and difference views
};

/// Every kind's name in the text form, in enum order.
const std::vector<std::string>& debugViewNames();
/// "final", "gbuffer-position[:LIGHT[:FACE]]", "gbuffer-normal[:LIGHT[:FACE]]", "map[:K]",
/// "coverage", "vpl", "wireframe", "difference". Indices are checked against the scene when drawn,
/// not here. Throws std::invalid_argument with one line (no prefix).
DebugView parseDebugView(std::string_view text);
std::string formatDebugView(const DebugView& view);

}  // namespace tallow::sss
