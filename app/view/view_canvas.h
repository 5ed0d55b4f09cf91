#pragma once
// The picture of the view window: the final image or a debug view is drawn into a texture of the
// image's own size (the rendered resolution), which is then copied into the image's place in the
// window (app/view/view_layout.h): pixel for pixel at scale 1, filtered when scaled to fit.
#include "app/view/view_layout.h"
#include "gpu/gl_objects.h"

namespace tallow::app {

/// Clears the window (windowW × windowH) and copies the width × height picture that `framebuffer`
/// reads (0: none yet) into `layout.image`.
void presentPicture(GLuint framebuffer, int width, int height, const ViewLayout& layout, int windowW, int windowH);

class ViewCanvas {
 public:
  /// The framebuffer to draw the picture into, width × height (reallocated when the size changes).
  GLuint target(int width, int height);
  /// Clears the window (width × height) and copies the picture into `layout.image`.
  void present(const ViewLayout& layout, int windowW, int windowH);
  /// The picture's texture (0 before target()), for a context that shares it.
  GLuint texture() const { return colour_.id(); }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  gpu::Texture colour_;
  gpu::Framebuffer framebuffer_;
  int width_ = 0, height_ = 0;
};

}  // namespace tallow::app
