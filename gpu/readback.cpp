#include "gpu/readback.h"

#include <utility>

namespace tallow::gpu {
namespace {
void flipRows(Image& image) {
  for (int y = 0; y < image.height / 2; ++y)
    for (int x = 0; x < image.width; ++x) std::swap(image.at(x, y), image.at(x, image.height - 1 - y));
}
}  // namespace

Image readColor(const Framebuffer& fb, int attachment, int width, int height) {
  Image image(width, height);
  GLint previous = 0;
  glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &previous);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, fb.id());
  glNamedFramebufferReadBuffer(fb.id(), GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(attachment));
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_FLOAT, image.pixels.data());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(previous));
  flipRows(image);
  return image;
}

Image readTexture(const Texture& texture) {
  Image image(texture.width(), texture.height());
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glGetTextureImage(texture.id(), 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(image.pixels.size() * sizeof(glm::vec4)),
                    image.pixels.data());
  flipRows(image);
  return image;
}

}  // namespace tallow::gpu
