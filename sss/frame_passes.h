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

/// camera.still (render.aa > 1): the frame just drawn folded into the still's weighted mean in the
/// camera target (sss/still_average.h); the renderer restarts the mean whenever a pass of the frame
/// ran with changed inputs, and moves the camera by the next sub-pixel offset otherwise.
class StillAveragePass final : public FramePass {
 public:
  std::string name() const override { return "camera.still"; }
  bool needed(const FrameState& state) const override { return state.settings.aaSamples > 1; }
  std::string reason(const FrameState& state) const override;
  PassIo io(const FrameState& state) const override;
  bool runsAgain(const FrameState&) const override { return true; }  // after every camera pass
  void run(FrameContext& context, bool changed) override;
};

/// camera.bloom (render.bloom > 0): the glare of the picture's bright light, an energy-conserving
/// PSF (sss/bloom.h), into the picture that is shown (window, PNG, video); the radiance stays.
class BloomPass final : public FramePass {
 public:
  std::string name() const override { return "camera.bloom"; }
  bool needed(const FrameState& state) const override { return state.settings.bloom > 0.0f; }
  std::string reason(const FrameState& state) const override;
  PassIo io(const FrameState& state) const override;
  bool runsAgain(const FrameState&) const override { return true; }  // after every camera pass
  bool afterPicture() const override { return true; }
  void run(FrameContext& context, bool changed) override;
};

/// camera.local_exposure (render.local_exposure > 0): the picture shown (after the glare) with its
/// shadows' base layer lifted toward mid grey (sss/local_exposure.h); the radiance stays.
class LocalExposurePass final : public FramePass {
 public:
  std::string name() const override { return "camera.local_exposure"; }
  bool needed(const FrameState& state) const override { return state.settings.localExposure > 0.0f; }
  std::string reason(const FrameState& state) const override;
  PassIo io(const FrameState& state) const override;
  bool runsAgain(const FrameState&) const override { return true; }  // after every camera pass
  bool afterPicture() const override { return true; }
  void run(FrameContext& context, bool changed) override;
};

}  // namespace tallow::sss
