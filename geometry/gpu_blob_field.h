#pragma once
// The animated blob (BlobField) evaluated on the GPU: Φ_t and its analytic gradient from the blob's
// centres at t as uniforms (shaders/fields/blob.glsl, the lines BlobField::value / gradient
// evaluate in C++). fill() writes a GpuDualContouring's lattice with a compute shader
// (shaders/fields/lattice.comp with FIELD_BLOB) and sets the uniforms of its analytic vertex normals: per
// frame, the CPU computes four centres (BlobField's constructor: a few sin() each) and sets
// uniforms; no lattice is sampled on the CPU, nothing is uploaded, nothing is read back.
#include "geometry/blob_field.h"
#include "geometry/gpu_dual_contouring.h"
#include "geometry/grid_sampler.h"
#include "gpu/program.h"
#include "gpu/shader_library.h"

namespace tallow::geometry {

class GpuBlobField {
 public:
  /// Builds the lattice program. Needs a current GL 4.5 context.
  explicit GpuBlobField(const gpu::ShaderLibrary& library);

  /// Fills `dc`'s lattice with `blob` at `frame`'s samples (frame.values unused: latticeOver's
  /// origin and cell size, frame.n == dc's n) and, when dc takes its normals from the blob
  /// (NormalSource::BlobGradient), sets them to this blob. No stall, no read-back.
  void fill(GpuDualContouring& dc, const BlobField& blob, const SampledLattice& frame);

  /// Sets the uniforms of shaders/fields/blob_uniforms.glsl on `program` to `blob`.
  static void setUniforms(gpu::Program& program, const BlobField& blob);

 private:
  gpu::Program lattice_;
};

}  // namespace tallow::geometry
