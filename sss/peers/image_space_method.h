#pragma once
// Image-space importance sampling of the dipole (`method=image-space`, sss/peers/image_space.h) as a
// translucency method: the camera's G-buffer once per accumulation, then a scatter and a combine
// pass per frame until image_space.frames are accumulated, read by the camera pass at the pixel.
#include "sss/translucency_method.h"

namespace tallow::sss {

namespace resource {
inline constexpr const char* kImageSpaceGBuffer = "image_space.gbuffer";
inline constexpr const char* kImageSpaceEstimate = "image_space.estimate";
inline constexpr const char* kImageSpaceAccumulation = "image_space.accumulation";
}  // namespace resource

/// image_space.gbuffer: position, normal and E F_t per pixel (deterministic).
class ImageSpaceGBufferPass final : public Pass {
 public:
  std::string name() const override { return "image_space.gbuffer"; }
  std::string reason(const FrameState& state) const override;
  PassIo io(const FrameState& state) const override;
  void run(FrameContext& context, bool changed) override;
};

/// image_space.scatter: the frame's sample pattern and the per-pixel estimate; the head of the
/// accumulation: anything it reads changing restarts it, and it runs until image_space.frames.
class ImageSpaceScatterPass final : public Pass {
 public:
  std::string name() const override { return "image_space.scatter"; }
  std::string reason(const FrameState& state) const override;
  PassIo io(const FrameState& state) const override;
  bool runsAgain(const FrameState& state) const override;
  bool refines() const override { return true; }
  void run(FrameContext& context, bool changed) override;

 private:
  int frames_ = 0;  ///< frames accumulated since the last restart
};

/// image_space.combine: the geometry-aware mean over the tile, added to the accumulation.
class ImageSpaceCombinePass final : public Pass {
 public:
  std::string name() const override { return "image_space.combine"; }
  std::string reason(const FrameState& state) const override;
  PassIo io(const FrameState& state) const override;
  void run(FrameContext& context, bool changed) override;
};

class ImageSpaceMethod final : public TranslucencyMethod {
 public:
  SssMethod id() const override { return SssMethod::ImageSpace; }
  void checkLimits(const FrameState& state) const override;
  std::vector<Pass*> passes(const FrameState& state) override;
  bool shadesTranslucent(const FrameState& state) const override;
  std::string surfaceShader() const override { return "peers/image_space/surface.glsl"; }
  void addMemory(const Scene& scene, const RenderSettings& settings, const BudgetSizes& sizes,
                 FrameMemory& memory) const override;
  std::string describeShading(const FrameState& state) const override;
  PassIo surfaceIo(const FrameState& state) const override;
  int surfaceUnits() const override { return 2; }  ///< the accumulated estimate and coverage
  void bindSurface(gpu::Program& program, const FrameContext& context, GLuint firstUnit) const override;
  /// The frames its estimate has accumulated (image_space.frames at most).
  double stillWeight(const FrameContext& context) const override;

 private:
  ImageSpaceGBufferPass gbuffer_;
  ImageSpaceScatterPass scatter_;
  ImageSpaceCombinePass combine_;
};

}  // namespace tallow::sss
