#include "sss/field_kind.h"

#include <stdexcept>

namespace tallow::sss {

geometry::SampledLattice FieldKindModel::sample(double timeS, int n) const {
  return geometry::sampleField(*at(timeS), bounds(), n);
}

std::unique_ptr<GpuFieldFill> FieldKindModel::gpuFill(const gpu::ShaderLibrary& /*shaders*/) const { return nullptr; }

// The kind's factory and the description questions: the only switches on FieldDesc::kind.

std::unique_ptr<FieldKindModel> makeFieldKind(const SceneObject& object) {
  if (object.shape != ShapeKind::Field)
    throw std::invalid_argument("FieldSource: object \"" + object.name + "\" is not a field");
  switch (object.field.kind) {
    case FieldKind::Blob: return field_kinds::makeBlob(object.field);
    case FieldKind::Candle: return field_kinds::makeCandle(object.field);
    case FieldKind::Mesh: return field_kinds::makeMesh(object);
  }
  throw std::logic_error("makeFieldKind: unknown field kind");
}

bool fieldAnimated(const FieldDesc& desc) {
  switch (desc.kind) {
    case FieldKind::Blob:
    case FieldKind::Candle: return true;
    case FieldKind::Mesh: return field_kinds::meshMelts(desc);
  }
  return false;
}

bool fieldCarriesFlame(const FieldDesc& desc) { return desc.kind == FieldKind::Candle; }

std::optional<geometry::CandleField> candleOf(const FieldDesc& desc, double timeS) {
  if (!fieldCarriesFlame(desc)) return std::nullopt;
  return geometry::CandleField(timeS, field_kinds::candleParams(desc));
}

}  // namespace tallow::sss
