#pragma once
// The camera's view of every object with the irradiance transmitted into the translucent ones
// (shaders/peers/image_space/gbuffer.frag): what the screen-space peers scatter from. Per pixel the
// world position with the translucent slot + 1 (0: opaque), the normal facing the camera, and
// E·F_t from every light with its shadow map; a depth buffer for the draw. Used by the image-space
// peer (Mertens et al. 2003, sss/peers/image_space.h) and the engines' diffusion profile
// (sss/peers/burley.h).
#include <cstddef>
#include <vector>

#include "gpu/gl_objects.h"
#include "gpu/program.h"
#include "gpu/shader_library.h"
#include "sss/render_settings.h"
#include "sss/scene.h"
#include "sss/scene_geometry.h"
#include "sss/shadow_pass.h"
#include "sss/view_setup.h"

namespace tallow::sss {

/// A width × height 2D target of `format` read texel by texel (nearest, clamped): what the
/// screen-space peers' passes write and read.
gpu::Texture screenTexture(GLenum format, int width, int height);
/// Its bytes.
std::size_t screenTextureBytes(GLenum format, int width, int height);

class CameraIrradianceGBuffer {
 public:
  explicit CameraIrradianceGBuffer(const gpu::ShaderLibrary& shaders);

  /// Draws every object at settings.width × settings.height (the targets follow the size).
  void render(const Scene& scene, const RenderSettings& settings, const SceneGeometry& geometry,
              const CameraView& camera, const ShadowPass& shadows);

  const gpu::Texture& positions() const { return position_; }  ///< RGBA32F: world point [m], slot + 1
  const gpu::Texture& normals() const { return normal_; }      ///< RGBA16F: the normal facing the camera
  const gpu::Texture& irradiance() const { return irradiance_; }  ///< RGBA32F: E·F_t [W/m²]
  /// Translucent slot of each scene object (−1 for opaque), valid after render().
  const std::vector<int>& slots() const { return slots_; }
  int width() const { return position_.width(); }
  std::size_t bytes() const;
  /// What render() allocates at width × height.
  static std::size_t bytesFor(int width, int height);

 private:
  gpu::Program program_;
  gpu::Texture position_, normal_, irradiance_, depth_;
  gpu::Framebuffer target_;
  std::vector<int> slots_;
};

}  // namespace tallow::sss
