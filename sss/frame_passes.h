#pragma once
// The passes every frame plans whatever its method: the field objects' isosurfaces, the shadow
// maps and the camera pass. Each says when the scene needs it (needed), why (reason) and what it
// reads and writes (io); the GPU state they fill lives in modules (FieldObjects, ShadowPass,
// SurfacePass) that outlive a frame.
#include <string>

#include "sss/pass.h"

namespace tallow::sss {

/// A pass of the frame itself (not of a method): planned when the scene needs it.
class FramePass : public Pass {
 public:
  virtual bool needed(const FrameState& state) const = 0;
};

/// field.sample: every field object at t (or at a new field.res) put on a lattice: a blob and a
/// melting mesh evaluated on the GPU from uniforms (the mesh's static grids uploaded once), the
/// others sampled on the CPU and uploaded (FieldObjects::sample).
class FieldSamplePass final : public FramePass {
 public:
  std::string name() const override { return "field.sample"; }
  bool needed(const FrameState& state) const override;
  std::string reason(const FrameState& state) const override;
  PassIo io(const FrameState& state) const override;
  void run(FrameContext& context, bool changed) override;
};

/// field.extract: GPU dual contouring of the sampled lattices into transform-feedback buffers.
class FieldExtractPass final : public FramePass {
 public:
  std::string name() const override { return "field.extract"; }
  bool needed(const FrameState& state) const override;
  std::string reason(const FrameState& state) const override;
  PassIo io(const FrameState& state) const override;
  void run(FrameContext& context, bool changed) override;
};

/// shadow.directional: one orthographic depth layer per directional light that casts shadows.
class DirectionalShadowPass final : public FramePass {
 public:
  std::string name() const override { return "shadow.directional"; }
  bool needed(const FrameState& state) const override;
  std::string reason(const FrameState& state) const override;
  PassIo io(const FrameState& state) const override;
  void run(FrameContext& context, bool changed) override;
};

/// shadow.point: one depth cube per point light that casts shadows.
class PointShadowPass final : public FramePass {
 public:
  std::string name() const override { return "shadow.point"; }
  bool needed(const FrameState& state) const override;
  std::string reason(const FrameState& state) const override;
  PassIo io(const FrameState& state) const override;
  void run(FrameContext& context, bool changed) override;
};

/// surface: the camera pass (SurfacePass), every frame: opaque objects Lambertian with direct
/// light, shadows and ambient; translucent ones as the frame's method says.
class CameraPass final : public FramePass {
 public:
  /// `method` gives the translucent part of the reason and of the reads.
  explicit CameraPass(const TranslucencyMethod& method) : method_(&method) {}
  void setMethod(const TranslucencyMethod& method) { method_ = &method; }
  std::string name() const override { return "surface"; }
  bool needed(const FrameState&) const override { return true; }
  std::string reason(const FrameState& state) const override;
  PassIo io(const FrameState& state) const override;
  /// Every frame: it draws the picture (the no-cache gather draws new samples each time).
  bool runsAgain(const FrameState&) const override { return true; }
  void run(FrameContext& context, bool changed) override;

 private:
  const TranslucencyMethod* method_;
  int frame_ = 0;              ///< frames drawn since the accumulation began: seeds the gather
  int accumulation_ = 0;       ///< FrameState::accumulation of the last frame
};

}  // namespace tallow::sss
