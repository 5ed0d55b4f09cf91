#include "geometry/extraction_path.h"

#include <stdexcept>
#include <string>

namespace tallow::geometry {

ExtractionPath parseExtractionPath(std::string_view name) {
  if (name == "geometry") return ExtractionPath::GeometryShader;
  if (name == "compute") return ExtractionPath::Compute;
  throw std::invalid_argument("unknown extraction path \"" + std::string(name) + "\" (geometry, compute)");
}

std::string_view extractionPathName(ExtractionPath path) {
  switch (path) {
    case ExtractionPath::GeometryShader: return "geometry";
    case ExtractionPath::Compute: return "compute";
  }
  return "?";
}

}  // namespace tallow::geometry
