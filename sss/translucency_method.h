#pragma once
// How translucent objects are shaded (parameter `method`): one interface that radiosity maps,
// no-cache, SSLPV, image-space and albedo implement (sss/methods.h lists them). A method adds its
// passes to the frame plan, between the shadow maps and the camera pass, and tells the camera pass
// (sss/surface_pass.h) how to shade the translucent pixels. The renderer never names a method:
// a new one is a class implementing this interface and a line in makeTranslucencyMethods().
#include <glad/gl.h>

#include <string>
#include <vector>

#include "gpu/program.h"
#include "sss/memory_budget.h"
#include "sss/pass.h"
#include "sss/render_settings.h"

namespace tallow::sss {

class TranslucencyMethod {
 public:
  virtual ~TranslucencyMethod() = default;
  /// The value of `method` that selects it.
  virtual SssMethod id() const = 0;
  /// Throws std::invalid_argument with one line naming the parameter when `state`'s settings exceed
  /// what this GPU (the current GL context) or the method's passes hold. Every method's limits are
  /// checked, not only the selected one's, so that a preset is refused whatever the method.
  virtual void checkLimits(const FrameState& /*state*/) const {}
  /// The passes this method adds for this frame, in order (empty when the scene has no translucent
  /// object). The objects are the method's own and keep their state between frames.
  virtual std::vector<Pass*> passes(const FrameState& state) = 0;
  /// True when the method shades this frame's translucent objects (false without any, and for the
  /// albedo baseline, which draws them as opaque ones).
  virtual bool shadesTranslucent(const FrameState& state) const = 0;
  /// The GLSL file (relative to shaders/) of its part of the camera pass: translucentShading and
  /// surroundingsIrradiance (camera/surface_method.glsl). The camera pass compiles one variant of
  /// shaders/surface.frag per method with it as TALLOW_SURFACE_METHOD.
  virtual std::string surfaceShader() const = 0;
  /// The camera pass's reason, this method's part: "translucent ones from …".
  virtual std::string describeShading(const FrameState& state) const = 0;
  /// What the camera pass reads for this method (inputs and resources), beyond its own.
  virtual PassIo surfaceIo(const FrameState& state) const = 0;
  /// Texture units the method's samplers in its camera-pass variant take (firstUnit … firstUnit + count − 1).
  virtual int surfaceUnits() const = 0;
  /// Sets the uniforms and samplers of its variant of the camera pass. Its samplers go to their
  /// units also when its passes made nothing to read (no translucent object): a sampler left on a
  /// unit of another type voids every draw.
  virtual void bindSurface(gpu::Program& program, const FrameContext& context, GLuint firstUnit) const = 0;
  /// Per translucent object, before its draw in the camera pass (the active method only).
  virtual void bindSurfaceObject(gpu::Program& /*program*/, const FrameContext& /*context*/, int /*objectIndex*/) const {}
  /// The weight of this frame's picture in a still's average (render.aa, sss/still_average.h): the
  /// samples its translucent estimate holds, relative to one frame's. A progressive method's frame k
  /// holds k frames of samples; a method that draws fresh samples each frame (or none) weighs 1.
  virtual double stillWeight(const FrameContext& /*context*/) const { return 1.0; }
  /// Adds to `memory` what its passes allocate on the GPU for a frame of `scene` with `settings`
  /// (sss/memory_budget.h; `sizes`: what the renderer chose for the auto sizes so far).
  virtual void addMemory(const Scene& /*scene*/, const RenderSettings& /*settings*/, const BudgetSizes& /*sizes*/,
                         FrameMemory& /*memory*/) const {}
  /// sss.maps=auto: true when the method draws maps whose count the renderer chooses from the
  /// coverage its camera pass (and its VPLs) count (sss/maps/map_count.h).
  virtual bool choosesMapCount(const FrameState& /*state*/) const { return false; }
  /// True when the method's VPLs count coverage too; they run only when the maps change, so their
  /// last counts stand for the frames after.
  virtual bool countsVplCoverage(const FrameState& /*state*/) const { return false; }
  /// The passes this method adds right after the camera pass, in order: what it adds to the picture
  /// from the receivers' G-buffer the camera pass left (CameraTarget::receiver, receiverAlbedo; the
  /// VPLs' emergent light on the opaque surroundings). Empty for methods that carry no such light.
  virtual std::vector<Pass*> afterCamera(const FrameState& /*state*/) { return {}; }
};

/// True when the scene has a translucent object.
bool anyTranslucent(const Scene& scene);

/// The albedo baseline (`method=albedo`): no passes; translucent objects are Lambertian with their
/// albedo, as opaque ones.
class AlbedoMethod final : public TranslucencyMethod {
 public:
  SssMethod id() const override { return SssMethod::Albedo; }
  std::vector<Pass*> passes(const FrameState&) override { return {}; }
  bool shadesTranslucent(const FrameState&) const override { return false; }
  std::string surfaceShader() const override { return "camera/surface_albedo.glsl"; }
  std::string describeShading(const FrameState&) const override;
  PassIo surfaceIo(const FrameState&) const override { return {}; }
  int surfaceUnits() const override { return 0; }
  void bindSurface(gpu::Program&, const FrameContext&, GLuint) const override {}
};

}  // namespace tallow::sss
