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
#include "sss/pass.h"
#include "sss/render_settings.h"

namespace tallow::sss {

/// What surface.frag computes B with for translucent pixels (its uniform uTranslucentMethod).
enum class SurfaceShading : int {
  None = 0,        ///< no transport: translucent objects are drawn like opaque ones, with their albedo
  Algorithm1 = 1,  ///< the scattered radiosity maps (maps/algorithm1.glsl)
  Gather = 2,      ///< the gather per pixel against the light G-buffers (maps/gather.glsl)
  ImageSpace = 3,  ///< the image-space accumulation at the pixel (peers/image_space/result.glsl)
  Sslpv = 4,       ///< SSLPV's accumulation grid (peers/sslpv/lookup.glsl)
};

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
  /// How surface.frag shades translucent pixels this frame (None without translucent objects).
  virtual SurfaceShading shading(const FrameState& state) const = 0;
  /// The camera pass's reason, this method's part: "translucent ones from …".
  virtual std::string describeShading(const FrameState& state) const = 0;
  /// What the camera pass reads for this method (inputs and resources), beyond its own.
  virtual PassIo surfaceIo(const FrameState& state) const = 0;
  /// Texture units the method's samplers in surface.frag take (firstUnit … firstUnit + count − 1).
  virtual int surfaceUnits() const = 0;
  /// Sets this method's uniforms and samplers of surface.frag. When `active` is false the method is
  /// not the frame's: its samplers still go to their own units (a sampler left on a unit of another
  /// type voids every draw) and its contributions (the VPLs' light on receivers) are off.
  virtual void bindSurface(gpu::Program& program, const FrameContext& context, GLuint firstUnit, bool active) const = 0;
  /// Per translucent object, before its draw in the camera pass (the active method only).
  virtual void bindSurfaceObject(gpu::Program& /*program*/, const FrameContext& /*context*/, int /*objectIndex*/) const {}
  /// The weight of this frame's picture in a still's average (render.aa, sss/still_average.h): the
  /// samples its translucent estimate holds, relative to one frame's. A progressive method's frame k
  /// holds k frames of samples; a method that draws fresh samples each frame (or none) weighs 1.
  virtual double stillWeight(const FrameContext& /*context*/) const { return 1.0; }
};

/// True when the scene has a translucent object.
bool anyTranslucent(const Scene& scene);

/// The albedo baseline (`method=albedo`): no passes; translucent objects are Lambertian with their
/// albedo, as opaque ones.
class AlbedoMethod final : public TranslucencyMethod {
 public:
  SssMethod id() const override { return SssMethod::Albedo; }
  std::vector<Pass*> passes(const FrameState&) override { return {}; }
  SurfaceShading shading(const FrameState&) const override { return SurfaceShading::None; }
  std::string describeShading(const FrameState&) const override;
  PassIo surfaceIo(const FrameState&) const override { return {}; }
  int surfaceUnits() const override { return 0; }
  void bindSurface(gpu::Program&, const FrameContext&, GLuint, bool) const override {}
};

}  // namespace tallow::sss
