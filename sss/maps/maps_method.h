#pragma once
// The scattered radiosity maps (`method=radiosity-maps`, the paper's Fig. 3 with its VPLs) and
// their no-cache variant (`method=no-cache`, Fig. 11) as translucency methods, with the passes
// they plan:
//   sss.light_gbuffer  step 1, the lights' G-buffers (RadiosityMaps::renderLightGBuffers);
//   sss.maps           step 2, K maps accumulated over sss.frames frames (progressive);
//   vpl                §3.4, virtual point lights on the outermost surface lighting the receivers;
// and step 3 in the camera pass: Algorithm 1 over the maps, or the gather per pixel (no-cache).
#include <cstdint>
#include <memory>

#include "sss/translucency_method.h"

namespace tallow::sss {

namespace resource {
inline constexpr const char* kLightGBuffers = "light_gbuffers";
inline constexpr const char* kRadiosityMaps = "radiosity_maps";
inline constexpr const char* kVpls = "vpls";
}  // namespace resource

/// sss.light_gbuffer: per directional light an orthographic layer, per point light a cube, of world
/// position, normal and object tag; deterministic, so it reruns only when what it reads changed.
class LightGBufferPass final : public Pass {
 public:
  std::string name() const override { return "sss.light_gbuffer"; }
  std::string reason(const FrameState& state) const override;
  PassIo io(const FrameState& state) const override;
  void run(FrameContext& context, bool changed) override;
};

/// sss.maps: the K scattered radiosity maps, one more frame of N samples per texel each run while
/// fewer than sss.frames are accumulated; anything it reads changing restarts the accumulation.
class RadiosityMapsPass final : public Pass {
 public:
  std::string name() const override { return "sss.maps"; }
  std::string reason(const FrameState& state) const override;
  PassIo io(const FrameState& state) const override;
  bool runsAgain(const FrameState& state) const override;
  bool refines() const override { return true; }
  void run(FrameContext& context, bool changed) override;

 private:
  int frames_ = 0;  ///< frames accumulated since the last restart (RadiosityMaps::frames)
  bool stillPending_ = false;  ///< RadiosityMaps::stillPending after the last run
  std::uint64_t restartKey_ = 0;  ///< fingerprint of the inputs whose change restarts the maps
  std::uint64_t restartKeyBesideK_ = 0;  ///< the same without sss.maps (a change of K alone: MapsUpdate::Resize)
  std::uint64_t motionKey_ = 0;          ///< time and the lights' placement and intensity
};

/// vpl.receivers: the VPLs' emergent light on the opaque receivers (Eq. 15), ρ/π · E_vpl added to
/// every opaque pixel of the camera's picture by a compute pass over the receivers' G-buffer the
/// camera pass left (VirtualPointLights::lightReceivers); after each camera pass.
class VplReceiversPass final : public Pass {
 public:
  std::string name() const override { return "vpl.receivers"; }
  std::string reason(const FrameState& state) const override;
  PassIo io(const FrameState& state) const override;
  void run(FrameContext& context, bool changed) override;
};

/// vpl: the VPLs of the paper's §3.4 from this frame's maps; again every frame when vpl.stable is off.
class VplPass final : public Pass {
 public:
  std::string name() const override { return "vpl"; }
  std::string reason(const FrameState& state) const override;
  PassIo io(const FrameState& state) const override;
  bool runsAgain(const FrameState& state) const override { return !state.settings.vpl.stable; }
  void run(FrameContext& context, bool changed) override;

 private:
  int frame_ = 0;  ///< frames with VPLs: seeds the directions when they are not stable
};

class RadiosityMapsMethod final : public TranslucencyMethod {
 public:
  /// `gbuffer` is shared with NoCacheMethod: one pass, one output, whichever method draws it.
  explicit RadiosityMapsMethod(std::shared_ptr<LightGBufferPass> gbuffer) : gbuffer_(std::move(gbuffer)) {}
  SssMethod id() const override { return SssMethod::RadiosityMaps; }
  void checkLimits(const FrameState& state) const override;
  std::vector<Pass*> passes(const FrameState& state) override;
  bool shadesTranslucent(const FrameState& state) const override;
  /// Algorithm 1; the VPLs' light on the surroundings in compute after the pass (lightSurroundings),
  /// or, where a test asks for the path before (VirtualPointLights::allowComputeReceivers), in it.
  std::string surfaceShader() const override;
  bool choosesMapCount(const FrameState& state) const override;
  void addMemory(const Scene& scene, const RenderSettings& settings, const BudgetSizes& sizes,
                 FrameMemory& memory) const override;
  bool countsVplCoverage(const FrameState& state) const override;
  std::vector<Pass*> afterCamera(const FrameState& state) override;
  std::string describeShading(const FrameState& state) const override;
  PassIo surfaceIo(const FrameState& state) const override;
  int surfaceUnits() const override { return 3; }  ///< the maps, their depth, the VPLs' shadow cubes
  void bindSurface(gpu::Program& program, const FrameContext& context, GLuint firstUnit) const override;
  /// The maps' accumulated frames: the frame after k frames of map samples weighs k.
  double stillWeight(const FrameContext& context) const override;

 private:
  std::shared_ptr<LightGBufferPass> gbuffer_;
  RadiosityMapsPass maps_;
  VplPass vpl_;
  VplReceiversPass vplReceivers_;
};

class NoCacheMethod final : public TranslucencyMethod {
 public:
  explicit NoCacheMethod(std::shared_ptr<LightGBufferPass> gbuffer) : gbuffer_(std::move(gbuffer)) {}
  SssMethod id() const override { return SssMethod::NoCache; }
  std::vector<Pass*> passes(const FrameState& state) override;
  bool shadesTranslucent(const FrameState& state) const override;
  std::string surfaceShader() const override { return "maps/surface_gather.glsl"; }
  void addMemory(const Scene& scene, const RenderSettings& settings, const BudgetSizes& sizes,
                 FrameMemory& memory) const override;
  std::string describeShading(const FrameState& state) const override;
  PassIo surfaceIo(const FrameState& state) const override;
  int surfaceUnits() const override { return 4; }  ///< the light G-buffers the gather reads
  void bindSurface(gpu::Program& program, const FrameContext& context, GLuint firstUnit) const override;

 private:
  std::shared_ptr<LightGBufferPass> gbuffer_;
};

}  // namespace tallow::sss
