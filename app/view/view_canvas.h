#pragma once
// The picture of the view window: the final image or a debug view is drawn into a texture of the
// image's own size (the rendered resolution), which is then copied into the image's place in the
// window (app/view/view_layout.h): pixel for pixel at scale 1, filtered when scaled to fit.
#include "app/view/view_layout.h"
#include "gpu/gl_objects.h"

namespace tallow::app {

class ViewCanvas {
 public:
  /// The framebuffer to draw the picture into, width × height (reallocated when the size changes).
  GLuint target(int width, int height);
  /// Clears the window (width × height) and copies the picture into `layout.image`.
  void present(const ViewLayout& layout, int windowW, int windowH);

 private:
  gpu::Texture colour_;
  gpu::Framebuffer framebuffer_;
  int width_ = 0, height_ = 0;
};

}  // namespace tallow::app
