#pragma once
// Draws a debug view (sss/debug_view.h) of the renderer's last frame into a framebuffer: the
// window's alternative to DisplayPass. Textures (light G-buffers, radiosity maps, coverage, the
// difference to a reference) are drawn by shaders/debug/texture_view.frag over the viewport;
// overlays (wireframe, VPLs) by shaders/debug/overlay.* over the tone-mapped image, dimmed where
// the camera's depth buffer has something in front.
#include <optional>
#include <string>

#include "gpu/gl_objects.h"
#include "gpu/image.h"
#include "gpu/program.h"
#include "gpu/shader_library.h"
#include "sss/debug_view.h"
#include "sss/renderer.h"

namespace tallow::sss {

class DebugViewPass {
 public:
  explicit DebugViewPass(const gpu::ShaderLibrary& shaders);

  /// The image the difference view compares with (linear radiance, top row first).
  void setReference(const gpu::Image& reference);
  bool hasReference() const { return reference_.id() != 0; }

  /// Draws `view` of `renderer`'s last frame (rendered from `scene` with `settings`, of the size
  /// width × height) into framebuffer `target`. Square textures (G-buffers, maps) are centred in
  /// the part right of `coveredLeft` pixels (a panel over the window's left side). When the frame
  /// has nothing to show for the view (no radiosity maps with this method, a light or map index
  /// beyond the scene's, no reference), draws the final image and returns why, in one line;
  /// returns "" otherwise.
  std::string render(const DebugView& view, Renderer& renderer, const Scene& scene,
                     const RenderSettings& settings, GLuint target, int width, int height, int coveredLeft = 0);

  /// How many G-buffer layers (cube faces) a light has and which texture layer holds it: for the
  /// panel's index sliders. Empty when the frame has no light G-buffers.
  struct LightLayer {
    bool cube = false;
    int layer = 0;  ///< directional: its array layer; point: its cube
  };
  static std::optional<LightLayer> lightLayer(const Scene& scene, int light);

 private:
  std::string drawTexture(const DebugView& view, const Renderer& renderer, const Scene& scene,
                          const RenderSettings& settings, int width, int height, int coveredLeft);
  void drawWireframe(const Renderer& renderer, const Scene& scene, int width, int height);
  std::string drawVpls(const Renderer& renderer, const Scene& scene, const RenderSettings& settings, int width,
                       int height);

  gpu::Program textureProgram_, overlayProgram_;
  gpu::VertexArray emptyVao_, pointsVao_;
  gpu::Buffer points_;
  gpu::Texture reference_;
};

}  // namespace tallow::sss
