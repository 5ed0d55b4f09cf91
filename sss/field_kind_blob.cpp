// The animated metaball blob (geometry::BlobField): evaluated on the GPU from its centres at t
// (geometry::GpuBlobField, shaders/fields/blob.glsl) with analytic normals.
#include <memory>

#include "geometry/gpu_blob_field.h"
#include "sss/field_kind.h"

namespace tallow::sss::field_kinds {
namespace {

class BlobKind final : public FieldKindModel {
 public:
  explicit BlobKind(const FieldDesc& desc) {
    params_.scale = desc.blobScale;
    bounds_ = geometry::BlobField(0.0, params_).bounds();  // the box of every t already
  }
  bool animated() const override { return true; }
  geometry::Aabb bounds() const override { return bounds_; }
  std::unique_ptr<geometry::ScalarField> at(double timeS) const override {
    return std::make_unique<geometry::BlobField>(timeS, params_);
  }
  geometry::NormalSource gpuNormals() const override { return geometry::NormalSource::BlobGradient; }
  std::unique_ptr<GpuFieldFill> gpuFill(const gpu::ShaderLibrary& shaders) const override;
  std::optional<geometry::BlobField> blobAt(double timeS) const override { return geometry::BlobField(timeS, params_); }

 private:
  geometry::BlobParams params_;
  geometry::Aabb bounds_;
};

class BlobFill final : public GpuFieldFill {
 public:
  BlobFill(const gpu::ShaderLibrary& shaders, const BlobKind& kind) : program_(shaders), kind_(kind) {}
  void fill(double timeS, geometry::GpuDualContouring& dc) override {
    program_.fill(dc, *kind_.blobAt(timeS), geometry::latticeOver(kind_.bounds(), dc.samplesPerAxis()));
  }

 private:
  geometry::GpuBlobField program_;
  const BlobKind& kind_;
};

std::unique_ptr<GpuFieldFill> BlobKind::gpuFill(const gpu::ShaderLibrary& shaders) const {
  return std::make_unique<BlobFill>(shaders, *this);
}

}  // namespace

std::unique_ptr<FieldKindModel> makeBlob(const FieldDesc& desc) { return std::make_unique<BlobKind>(desc); }

}  // namespace tallow::sss::field_kinds
