#include "app/view/view_canvas.h"

#include <cmath>

namespace tallow::app {
namespace {
/// Around the picture (letterbox bars): the dark grey of the panel's style, so bars read as frame.
constexpr float kBackground[4] = {0.06f, 0.06f, 0.07f, 1.0f};
}  // namespace

GLuint ViewCanvas::target(int width, int height) {
  if (width != width_ || height != height_ || !framebuffer_.id()) {
    // RGBA8, not sRGB: the display and debug shaders write sRGB-encoded values themselves, and the
    // copy must carry those bytes to the window unchanged.
    colour_ = gpu::Texture::create2D(GL_RGBA8, width, height);
    colour_.setFilter(GL_LINEAR, GL_LINEAR);
    framebuffer_ = gpu::Framebuffer();
    framebuffer_.attachColor(0, colour_);
    framebuffer_.setDrawBuffers(1);
    framebuffer_.checkComplete("view canvas");
    width_ = width;
    height_ = height;
  }
  return framebuffer_.id();
}

void ViewCanvas::present(const ViewLayout& layout, int windowW, int windowH) {
  presentPicture(framebuffer_.id(), width_, height_, layout, windowW, windowH);
}

void presentPicture(GLuint framebuffer, int width, int height, const ViewLayout& layout, int windowW, int windowH) {
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glViewport(0, 0, windowW, windowH);
  glDisable(GL_SCISSOR_TEST);  // a blit obeys the scissor test
  glClearColor(kBackground[0], kBackground[1], kBackground[2], kBackground[3]);
  glClear(GL_COLOR_BUFFER_BIT);
  if (layout.image.empty() || !framebuffer) return;
  // Layout boxes count rows from the top; GL's from the bottom.
  const PixelBox& b = layout.image;
  const int y0 = windowH - (b.y + b.height), y1 = windowH - b.y;
  const bool exact = b.width == width && b.height == height;
  glBlitNamedFramebuffer(framebuffer, 0, 0, 0, width, height, b.x, y0, b.x + b.width, y1, GL_COLOR_BUFFER_BIT,
                         exact ? GL_NEAREST : GL_LINEAR);
}

}  // namespace tallow::app
