#pragma once
// Which shader stages run dual contouring's vertex and quad passes (parameter field.extraction):
// geometry shaders with transform feedback (the radiosity-maps paper's §4 path), or compute
// shaders writing the same records into the same buffers, drawn indirectly. The second keeps the
// work off the raster units, of which some GPUs have few (Hopper: vertex, geometry and fragment
// shaders run on two TPCs of the H100/H200). See geometry/gpu_dual_contouring.h.
#include <string_view>

namespace tallow::geometry {

enum class ExtractionPath {
  GeometryShader,  ///< cells.vert + vertices.geom / quads.geom, captured by transform feedback
  Compute,         ///< vertices.comp / quads.comp, appended with atomics, drawn by glDrawArraysIndirect
};

/// The default of field.extraction and of GpuDualContouring: compute, measured faster on llvmpipe
/// (`tallow probe extraction`, docs/RESULTS.md) and projected faster on GPUs with few raster units
/// (docs/device-bench.md).
inline constexpr ExtractionPath kDefaultExtraction = ExtractionPath::Compute;

/// "geometry" | "compute"; throws std::invalid_argument otherwise.
ExtractionPath parseExtractionPath(std::string_view name);
std::string_view extractionPathName(ExtractionPath path);

}  // namespace tallow::geometry
