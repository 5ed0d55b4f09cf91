#include "support/field_compare.h"

#include <algorithm>

#include "support/mesh_checks.h"

namespace tallow::test {

const sss::DrawItem* fieldItem(const sss::Renderer& renderer) {
  const auto& items = renderer.geometry().items();
  const auto it = std::find_if(items.begin(), items.end(), [](const sss::DrawItem& i) { return i.field != nullptr; });
  return it == items.end() ? nullptr : &*it;
}

FieldComparison compareWithCpuSampledPath(const geometry::GpuDualContouring& rendered, const sss::FieldSource& source,
                                          double t, int res, const gpu::ShaderLibrary& shaders,
                                          geometry::VertexPlacement placement) {
  FieldComparison c;
  c.gpuMesh = rendered.readBack();
  c.cpuLattice = source.sample(t, res);
  geometry::GpuDualContouring cpu(shaders, res, placement);
  cpu.upload(c.cpuLattice);
  cpu.extract();
  c.cpuMesh = cpu.readBack();
  const double cell = c.cpuLattice.cellSize;
  c.hausdorff = hausdorffDistance(c.gpuMesh, c.cpuMesh, cell, cell) / cell;
  c.triangleDifference = static_cast<long>(c.gpuMesh.triangles.size()) - static_cast<long>(c.cpuMesh.triangles.size());
  return c;
}

}  // namespace tallow::test
