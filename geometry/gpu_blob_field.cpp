#include "geometry/gpu_blob_field.h"

#include <array>
#include <stdexcept>
#include <string>

namespace tallow::geometry {

GpuBlobField::GpuBlobField(const gpu::ShaderLibrary& library)
    : lattice_(library, {{{GL_COMPUTE_SHADER, "fields/lattice.comp"}}, {"FIELD_BLOB"}}) {}

void GpuBlobField::setUniforms(gpu::Program& program, const BlobField& blob) {
  std::array<glm::vec3, BlobParams::kBlobCount> centres{};
  for (int i = 0; i < BlobParams::kBlobCount; ++i)
    centres[static_cast<std::size_t>(i)] = glm::vec3(blob.unscaledCentre(i));
  const BlobParams& p = blob.params();
  program.set("uBlobCentres", centres.data(), BlobParams::kBlobCount);
  program.set("uBlobSigma", static_cast<float>(p.sigma));
  program.set("uBlobIso", static_cast<float>(p.iso));
  program.set("uBlobScale", static_cast<float>(p.scale));
}

void GpuBlobField::fill(GpuDualContouring& dc, const BlobField& blob, const SampledLattice& frame) {
  if (frame.n != dc.samplesPerAxis())
    throw std::runtime_error("GpuBlobField::fill: lattice has " + std::to_string(frame.n) +
                             " samples per axis, the extractor " + std::to_string(dc.samplesPerAxis()));
  setUniforms(lattice_, blob);
  dc.fillOnGpu(lattice_, frame.origin, frame.cellSize);
  if (dc.normalSource() == NormalSource::BlobGradient) setUniforms(dc.normalProgram(), blob);
}

}  // namespace tallow::geometry
