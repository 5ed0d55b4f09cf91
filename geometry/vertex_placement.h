#pragma once
// Where dual contouring puts the vertex of a surface patch in a cell (parameter field.placement):
// the mass point of its edge crossings (surface nets, Gibson 1998) or the minimum of the
// probabilistic quadric of their tangent planes (Trettner & Kobbelt 2020), kept inside the cell.
// See shaders/dual_contouring/qef.glsl.
#include <string>
#include <string_view>

namespace tallow::geometry {

enum class VertexPlacement {
  Mass,  ///< mean of the patch's edge crossings: smooth, rounds sharp edges and corners off
  Qef,   ///< minimum of the tangent planes' quadric, regularised toward the mass point
};

/// The default of field.placement and of GpuDualContouring: the QEF, which measured closer to the
/// exact surface on sharp and smooth shapes alike (docs/presets.md, `tallow probe placement`).
inline constexpr VertexPlacement kDefaultPlacement = VertexPlacement::Qef;

/// "mass" | "qef"; throws std::invalid_argument otherwise.
VertexPlacement parseVertexPlacement(std::string_view name);
std::string_view vertexPlacementName(VertexPlacement placement);

}  // namespace tallow::geometry
