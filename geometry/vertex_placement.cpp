#include "geometry/vertex_placement.h"

#include <stdexcept>

namespace tallow::geometry {

VertexPlacement parseVertexPlacement(std::string_view name) {
  if (name == "mass") return VertexPlacement::Mass;
  if (name == "qef") return VertexPlacement::Qef;
  throw std::invalid_argument("unknown vertex placement \"" + std::string(name) + "\" (mass, qef)");
}

std::string_view vertexPlacementName(VertexPlacement placement) {
  switch (placement) {
    case VertexPlacement::Mass: return "mass";
    case VertexPlacement::Qef: return "qef";
  }
  return "?";
}

}  // namespace tallow::geometry
