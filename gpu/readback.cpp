#include "gpu/readback.h"

#include <algorithm>
#include <atomic>
#include <stdexcept>
#include <utility>

namespace tallow::gpu {
namespace {
std::atomic<std::uint64_t> reads{0};

void flipRows(Image& image) {
  for (int y = 0; y < image.height / 2; ++y)
    for (int x = 0; x < image.width; ++x) std::swap(image.at(x, y), image.at(x, image.height - 1 - y));
}
}  // namespace

std::uint64_t targetReads() { return reads.load(); }

Image readColor(const Framebuffer& fb, int attachment, int width, int height) {
  ++reads;
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
  ++reads;
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
  ++reads;
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

namespace tallow::gpu {

std::uint64_t AsyncReadback::issue(const std::vector<const Texture*>& textures) {
  Slot& slot = slots_[issued_ % kSlots];
  if (slot.ticket != 0) throw std::logic_error("AsyncReadback::issue: the slot's earlier read was not fetched");
  slot.buffers.resize(textures.size());
  slot.sizes.resize(textures.size());
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  for (std::size_t i = 0; i < textures.size(); ++i) {
    const Texture& t = *textures[i];
    const std::size_t bytes = static_cast<std::size_t>(t.width()) * static_cast<std::size_t>(t.height()) * sizeof(glm::vec4);
    if (slot.buffers[i].size() != bytes) slot.buffers[i] = Buffer(bytes, nullptr, GL_CLIENT_STORAGE_BIT);
    slot.sizes[i] = {t.width(), t.height()};
    ++reads;
    // The pack buffer binding is this call's only: bound for the copy, unbound after it.
    glBindBuffer(GL_PIXEL_PACK_BUFFER, slot.buffers[i].id());
    glGetTextureImage(t.id(), 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(bytes), nullptr);
  }
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  slot.fence = Fence::insert();
  slot.ticket = ++issued_;
  return slot.ticket;
}

std::vector<Image> AsyncReadback::fetch(std::uint64_t ticket) {
  Slot& slot = slots_[(ticket - 1) % kSlots];
  if (ticket == 0 || slot.ticket != ticket) throw std::logic_error("AsyncReadback::fetch: no such read pending");
  slot.fence.wait();
  std::vector<Image> images;
  images.reserve(slot.sizes.size());
  for (std::size_t i = 0; i < slot.sizes.size(); ++i) {
    Image image(slot.sizes[i][0], slot.sizes[i][1]);
    slot.buffers[i].download(0, image.pixels.size() * sizeof(glm::vec4), image.pixels.data());
    flipRows(image);
    images.push_back(std::move(image));
  }
  slot.ticket = 0;
  return images;
}

}  // namespace tallow::gpu
