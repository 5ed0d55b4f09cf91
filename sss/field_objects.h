#pragma once
// The field objects of a scene (ShapeKind::Field): each frame whose time (or field.res) changed,
// the field at that time is sampled on the CPU over a lattice, uploaded, and isosurfaced on the GPU
// by GpuDualContouring; otherwise the last transform-feedback mesh is drawn again. Each object's
// field, bounds and sampling come from its sss::FieldSource (shared with `tallow mesh` / `field`).
#include <memory>
#include <vector>

#include "geometry/gpu_dual_contouring.h"
#include "geometry/scalar_field.h"
#include "gpu/shader_library.h"
#include "sss/scene.h"
#include "sss/scene_geometry.h"

namespace tallow::sss {

class FieldObjects {
 public:
  /// Builds the time-independent parts (a mesh field's level set). Throws std::runtime_error
  /// naming the file when a mesh field's file is missing or broken.
  FieldObjects(const gpu::ShaderLibrary& shaders, const Scene& scene);
  ~FieldObjects();

  static bool any(const Scene& scene);
  /// True when some field object changes with time.
  bool animated() const;
  bool empty() const { return entries_.empty(); }
  /// True when some field must be sampled and extracted again for time t at `res` samples per axis
  /// with vertices placed by `placement`: nothing extracted yet, res or placement changed, or t
  /// changed for an animated field (blob, candle).
  bool stale(double timeS, int res, geometry::VertexPlacement placement) const;
  /// CPU sampling at t and upload of every stale field (pass "field.sample"); re-attaches the
  /// extractors to `geometry` (call geometry.update afterwards).
  void sample(double timeS, int res, geometry::VertexPlacement placement, SceneGeometry& geometry);
  /// GPU extraction of every field sampled by the last sample() (pass "field.extract").
  void extract();
  /// Triangles of the last extractions. Reads a transform-feedback query, so it waits for the
  /// GPU to finish the last extraction (a stall): for stats, not for the frame loop.
  std::size_t triangleCount() const;
  std::size_t bytes() const;

  struct Entry;

 private:
  const gpu::ShaderLibrary& shaders_;
  std::vector<std::unique_ptr<Entry>> entries_;
};

}  // namespace tallow::sss
