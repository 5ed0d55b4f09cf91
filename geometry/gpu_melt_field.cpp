#include "geometry/gpu_melt_field.h"

#include <stdexcept>
#include <string>

namespace tallow::geometry {

namespace {
/// fields/melt_uniforms.glsl's `binding` of MeltGridBuffer.
constexpr GLuint kGridBinding = 0;
}  // namespace

GpuMeltField::GpuMeltField(const gpu::ShaderLibrary& library)
    : lattice_(library, {{{GL_COMPUTE_SHADER, "fields/mesh_melt_lattice.comp"}}}) {}

void GpuMeltField::fill(GpuDualContouring& dc, const MeltAt& at, const SampledLattice& frame) {
  if (frame.n != dc.samplesPerAxis())
    throw std::runtime_error("GpuMeltField::fill: lattice has " + std::to_string(frame.n) +
                             " samples per axis, the extractor " + std::to_string(dc.samplesPerAxis()));
  if (!at.grids) throw std::logic_error("GpuMeltField::fill: no grids");
  const MeltGrids& grids = *at.grids;
  if (uploaded_ != at.grids) {  // once per preset load: the grids never change afterwards
    buffer_ = gpu::Buffer(grids.bytes(), grids.nanoVdb.data(), 0);
    uploaded_ = at.grids;
    ++uploads_;
  }
  const MeltState& s = at.state;
  lattice_.set("uMeltAnchor", glm::vec3(grids.anchor));
  lattice_.set("uMeltHeightScale", static_cast<float>(s.heightScale));
  lattice_.set("uMeltInvVoxel", static_cast<float>(1.0 / grids.voxelSize));
  lattice_.set("uMeltGridA", static_cast<int>(s.gridA));
  lattice_.set("uMeltGridB", static_cast<int>(s.gridB));
  lattice_.set("uMeltBlend", static_cast<float>(s.blend));
  lattice_.set("uMeltPuddleRadius", static_cast<float>(s.puddleRadius));
  lattice_.set("uMeltPuddleHeight", static_cast<float>(s.puddleHeight));
  lattice_.set("uMeltJoinRadius", static_cast<float>(s.joinRadius));
  lattice_.set("uMeltBoxLo", glm::vec3(grids.backgroundBoxLo()));
  lattice_.set("uMeltBoxHi", glm::vec3(grids.backgroundBoxHi()));
  lattice_.set("uMeltBackground", static_cast<float>(grids.bandWidth));
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kGridBinding, buffer_.id());
  dc.fillOnGpu(lattice_, frame.origin, frame.cellSize);
}

}  // namespace tallow::geometry
