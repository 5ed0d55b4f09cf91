// The melting candle (geometry::CandleField): evaluated on the GPU from its shape at t
// (geometry::GpuCandleField, shaders/fields/candle.glsl) with analytic normals, over the box of its
// whole life so that wax that does not change keeps its vertices.
#include <memory>

#include "geometry/gpu_candle_field.h"
#include "sss/field_kind.h"

namespace tallow::sss::field_kinds {

geometry::CandleParams candleParams(const FieldDesc& desc) {
  geometry::CandleParams p;
  p.durationS = desc.candleDurationS;
  p.timeScale = desc.candleTimeScale;
  p.dripCount = desc.candleDrips;
  p.seed = desc.candleSeed;
  return p;
}

namespace {

class CandleKind final : public FieldKindModel {
 public:
  explicit CandleKind(const FieldDesc& desc)
      : params_(candleParams(desc)), bounds_(geometry::CandleField::lifetimeBounds(params_)) {}
  bool animated() const override { return true; }
  geometry::Aabb bounds() const override { return bounds_; }
  std::unique_ptr<geometry::ScalarField> at(double timeS) const override {
    return std::make_unique<geometry::CandleField>(timeS, params_);
  }
  geometry::NormalSource gpuNormals() const override { return geometry::NormalSource::CandleGradient; }
  std::unique_ptr<GpuFieldFill> gpuFill(const gpu::ShaderLibrary& shaders) const override;
  std::optional<geometry::CandleField> candleAt(double timeS) const override {
    return geometry::CandleField(timeS, params_);
  }

 private:
  geometry::CandleParams params_;
  geometry::Aabb bounds_;
};

class CandleFill final : public GpuFieldFill {
 public:
  CandleFill(const gpu::ShaderLibrary& shaders, const CandleKind& kind) : program_(shaders), kind_(kind) {}
  void fill(double timeS, geometry::GpuDualContouring& dc) override {
    program_.fill(dc, *kind_.candleAt(timeS), geometry::latticeOver(kind_.bounds(), dc.samplesPerAxis()));
  }

 private:
  geometry::GpuCandleField program_;
  const CandleKind& kind_;
};

std::unique_ptr<GpuFieldFill> CandleKind::gpuFill(const gpu::ShaderLibrary& shaders) const {
  return std::make_unique<CandleFill>(shaders, *this);
}

}  // namespace

std::unique_ptr<FieldKindModel> makeCandle(const FieldDesc& desc) { return std::make_unique<CandleKind>(desc); }

}  // namespace tallow::sss::field_kinds
