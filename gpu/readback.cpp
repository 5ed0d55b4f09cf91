#include "gpu/readback.h"

#include <algorithm>
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

namespace tallow::gpu {

std::vector<std::uint8_t> readWindowRgb8(int width, int height) {
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3);
  GLint previous = 0;
  glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &previous);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(previous));
  // GL's row 0 is the bottom; files store the top row first.
  const std::size_t row = static_cast<std::size_t>(width) * 3;
  for (int y = 0; y < height / 2; ++y)
    std::swap_ranges(rgb.begin() + static_cast<std::ptrdiff_t>(y * row), rgb.begin() + static_cast<std::ptrdiff_t>((y + 1) * row),
                     rgb.begin() + static_cast<std::ptrdiff_t>((height - 1 - y) * row));
  return rgb;
}

}  // namespace tallow::gpu
