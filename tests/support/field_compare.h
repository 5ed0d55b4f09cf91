#pragma once
// The renderer's field mesh, filled on the GPU, against the mesh of the CPU-sampled path
// (FieldSource::sample → GpuDualContouring::upload/extract/readBack) at the same t, placement and
// resolution: the shared part of the blob, candle and melting-mesh GPU tests. Each test keeps its
// own thresholds and checks.
#include "geometry/gpu_dual_contouring.h"
#include "geometry/grid_sampler.h"
#include "geometry/triangle_mesh.h"
#include "gpu/shader_library.h"
#include "sss/field_source.h"
#include "sss/renderer.h"

namespace tallow::test {

/// The renderer's first draw item with a field (the field object's), or nullptr when it has none.
const sss::DrawItem* fieldItem(const sss::Renderer& renderer);

struct FieldComparison {
  geometry::TriangleMesh gpuMesh;       ///< the renderer's extraction, read back
  geometry::SampledLattice cpuLattice;  ///< source.sample(t, res)
  geometry::TriangleMesh cpuMesh;       ///< cpuLattice uploaded and extracted at the same res and placement
  double hausdorff = 0.0;               ///< Hausdorff distance of the two meshes, in cells of cpuLattice
  long triangleDifference = 0;          ///< gpuMesh's triangles − cpuMesh's
};

/// Reads back `rendered` (the renderer's field at t) and extracts the CPU-sampled lattice of
/// `source` at t on res³ points with `placement`, using `shaders` in the current context.
FieldComparison compareWithCpuSampledPath(const geometry::GpuDualContouring& rendered, const sss::FieldSource& source,
                                          double t, int res, const gpu::ShaderLibrary& shaders,
                                          geometry::VertexPlacement placement);

}  // namespace tallow::test
