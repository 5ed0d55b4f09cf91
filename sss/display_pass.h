#pragma once
// Tone maps the linear HDR target into an 8-bit sRGB image (the window, or a texture).
#include "gpu/gl_objects.h"
#include "gpu/program.h"
#include "gpu/tonemap.h"

namespace tallow::sss {

class DisplayPass {
 public:
  explicit DisplayPass(const gpu::ShaderLibrary& shaders);
  /// Draws `radiance` tone mapped into framebuffer `target` (0 = the window) over its viewport, as
  /// 8-bit levels dithered like the PNG writer's (Dither::On), or as the encoded values themselves.
  void render(const gpu::Texture& radiance, GLuint target, int width, int height, const gpu::ToneMapSettings& toneMap,
              gpu::Dither dither = gpu::Dither::On);

 private:
  gpu::Program program_;
  gpu::VertexArray emptyVao_;  ///< core profile needs a bound VAO even for attribute-less draws
};

}  // namespace tallow::sss
