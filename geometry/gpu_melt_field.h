#pragma once
// A melting mesh field (MeshLevelSetField::melted, geometry/mesh_melt.h) evaluated on the GPU: its
// static NanoVDB grids in a shader storage buffer, uploaded once (the first fill of those grids),
// and per frame only the melt's scalars at t as uniforms; shaders/fields/mesh_melt_lattice.comp
// fills a GpuDualContouring's lattice with shaders/fields/melt.glsl, the lines the CPU evaluates in
// double. No lattice is sampled on the CPU, nothing is uploaded per frame, nothing is read back.
#include <cstddef>
#include <memory>

#include "geometry/gpu_dual_contouring.h"
#include "geometry/grid_sampler.h"
#include "geometry/mesh_melt.h"
#include "gpu/gl_objects.h"
#include "gpu/program.h"
#include "gpu/shader_library.h"

namespace tallow::geometry {

class GpuMeltField {
 public:
  /// Builds the lattice program. Needs a current GL 4.5 context.
  explicit GpuMeltField(const gpu::ShaderLibrary& library);

  /// Fills `dc`'s lattice with the melt `at` over `frame`'s samples (frame.values unused, frame.n
  /// == dc's n). Uploads at.grids into the storage buffer when it holds other grids (once per
  /// preset load); otherwise sets uniforms and dispatches. No stall, no read-back.
  void fill(GpuDualContouring& dc, const MeltAt& at, const SampledLattice& frame);

  std::size_t gridUploadCount() const { return uploads_; }  ///< uploads of static grids so far
  std::size_t bytes() const { return buffer_.size(); }      ///< GPU memory of the grids

 private:
  gpu::Program lattice_;
  gpu::Buffer buffer_;
  std::shared_ptr<const MeltGrids> uploaded_;  ///< the grids the buffer holds (kept alive: no address reuse)
  std::size_t uploads_ = 0;
};

}  // namespace tallow::geometry
