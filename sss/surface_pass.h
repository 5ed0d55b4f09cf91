#pragma once
// Lambertian shading of every shape, lit by the scene's lights with shadows and a uniform
// ambient sky, into a linear HDR target with depth.
#include "gpu/gl_objects.h"
#include "gpu/program.h"
#include "sss/maps/radiosity_maps.h"
#include "sss/maps/virtual_point_lights.h"
#include "sss/peers/image_space.h"
#include "sss/peers/sslpv.h"
#include "sss/scene.h"
#include "sss/scene_geometry.h"
#include "sss/shadow_pass.h"
#include "sss/view_setup.h"

namespace tallow::sss {

/// Upper bounds of the shader's light arrays (shaders/common/lights.glsl).
constexpr int kMaxDirectionalLights = 32;
constexpr int kMaxPointLights = 8;

/// Where the camera pass takes the translucent objects' scattered radiosity B from: the frame's
/// method sets one of these (the renderer's passes that produced it); none set: albedo shading.
struct TranslucentSource {
  const RadiosityMaps* maps = nullptr;        ///< Algorithm 1 over the scattered radiosity maps
  const RadiosityMaps* noCache = nullptr;     ///< the gather per pixel against these light G-buffers
  const ImageSpaceSss* imageSpace = nullptr;  ///< the image-space accumulation at the pixel
  const Sslpv* sslpv = nullptr;               ///< SSLPV's accumulation grid
  bool any() const { return maps || noCache || imageSpace || sslpv; }
};

class SurfacePass {
 public:
  explicit SurfacePass(const gpu::ShaderLibrary& shaders);
  /// The scene's environment map (lat-long radiance, sss::Environment conventions) for the
  /// specular reflection on translucent objects; reads the file (throws std::runtime_error).
  void setEnvironment(const Environment& environment);
  /// Draws into `target` (already sized and cleared by the caller). With `source.maps`,
  /// translucent objects are shaded from the scattered radiosity maps (Algorithm 1, Eq. 5); with
  /// `noCache` (not null: its light G-buffers), by the gather per pixel (seeds from `frame`); with
  /// `imageSpace`, from its accumulation at the pixel; with `sslpv`, from its accumulation grid
  /// (Eqs. 6–7). With `vpls` (not null), opaque objects also receive the VPLs' emergent light.
  void render(const Scene& scene, const RenderSettings& settings, const SceneGeometry& geometry,
              const CameraView& camera, const ShadowPass& shadows, const TranslucentSource& source,
              const VirtualPointLights* vpls, int frame, const gpu::Framebuffer& target, int width, int height);

 private:
  gpu::Program program_;
  gpu::Texture environment_;
  float environmentRotationDeg_ = 0.0f, environmentScale_ = 1.0f;
};

}  // namespace tallow::sss
