#pragma once
// Subsurface light propagation volumes (`method=sslpv`, sss/peers/sslpv.h) as a translucency
// method: four deterministic passes that rerun only when what they read changed, and the camera
// pass reading the accumulation grid (Eqs. 6–7).
#include "sss/translucency_method.h"

namespace tallow::sss {

namespace resource {
inline constexpr const char* kSslpvMedium = "sslpv.medium";
inline constexpr const char* kSslpvLightGBuffers = "sslpv.light_gbuffers";
inline constexpr const char* kSslpvInjection = "sslpv.injection";
inline constexpr const char* kSslpvAccumulation = "sslpv.accumulation";
}  // namespace resource

/// sslpv.voxelize: the medium grid fitted to the translucent objects, their coefficients per cell.
class SslpvVoxelizePass final : public Pass {
 public:
  std::string name() const override { return "sslpv.voxelize"; }
  std::string reason(const FrameState& state) const override;
  PassIo io(const FrameState& state) const override;
  void run(FrameContext& context, bool changed) override;
};

/// sslpv.light_gbuffer: the lights' G-buffers at sslpv.inject_size.
class SslpvLightGBufferPass final : public Pass {
 public:
  std::string name() const override { return "sslpv.light_gbuffer"; }
  std::string reason(const FrameState& state) const override;
  PassIo io(const FrameState& state) const override;
  void run(FrameContext& context, bool changed) override;
};

/// sslpv.inject: Eq. 1 per G-buffer texel into the propagation grid.
class SslpvInjectPass final : public Pass {
 public:
  std::string name() const override { return "sslpv.inject"; }
  std::string reason(const FrameState& state) const override;
  PassIo io(const FrameState& state) const override;
  void run(FrameContext& context, bool changed) override;
};

/// sslpv.propagate: sslpv.steps propagation steps into the accumulation grid.
class SslpvPropagatePass final : public Pass {
 public:
  std::string name() const override { return "sslpv.propagate"; }
  std::string reason(const FrameState& state) const override;
  PassIo io(const FrameState& state) const override;
  void run(FrameContext& context, bool changed) override;
};

class SslpvMethod final : public TranslucencyMethod {
 public:
  SssMethod id() const override { return SssMethod::Sslpv; }
  void checkLimits(const FrameState& state) const override;
  std::vector<Pass*> passes(const FrameState& state) override;
  bool shadesTranslucent(const FrameState& state) const override;
  std::string surfaceShader() const override { return "peers/sslpv/surface.glsl"; }
  void addMemory(const Scene& scene, const RenderSettings& settings, const BudgetSizes& sizes,
                 FrameMemory& memory) const override;
  std::string describeShading(const FrameState& state) const override;
  PassIo surfaceIo(const FrameState& state) const override;
  int surfaceUnits() const override { return 4; }  ///< the accumulation grid per band, the medium
  void bindSurface(gpu::Program& program, const FrameContext& context, GLuint firstUnit) const override;

 private:
  SslpvVoxelizePass voxelize_;
  SslpvLightGBufferPass gbuffer_;
  SslpvInjectPass inject_;
  SslpvPropagatePass propagate_;
};

}  // namespace tallow::sss
