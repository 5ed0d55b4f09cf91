#include "sss/still_average.h"

#include <stdexcept>

namespace tallow::sss {

StillAverage::StillAverage(const gpu::ShaderLibrary& shaders)
    : program_(shaders, {{{GL_COMPUTE_SHADER, "camera/still_average.comp"}}}) {}

std::size_t StillAverage::bytesFor(int width, int height) {
  return 2 * gpu::Texture::bytesFor(GL_TEXTURE_2D, GL_RGBA32F, width, height, 1, 1) +
         gpu::Texture::bytesFor(GL_TEXTURE_2D, GL_R32F, width, height, 1, 1);
}

void StillAverage::add(const gpu::Texture& radiance, const gpu::Texture& translucent, double weight, bool first) {
  if (!(weight > 0.0)) throw std::logic_error("still average: a frame's weight must be positive");
  if (translucent.width() != radiance.width() || translucent.height() != radiance.height())
    throw std::logic_error("still average: the translucent part's size differs from the radiance's");
  if (!rest_.id() || rest_.width() != radiance.width() || rest_.height() != radiance.height()) {
    rest_ = gpu::Texture::create2D(GL_RGBA32F, radiance.width(), radiance.height());
    translucentSum_ = gpu::Texture::create2D(GL_RGBA32F, radiance.width(), radiance.height());
    translucentShare_ = gpu::Texture::create2D(GL_R32F, radiance.width(), radiance.height());
    first = true;
  }
  frames_ = first ? 1 : frames_ + 1;
  constexpr GLuint kGroup = 16;  // still_average.comp's local size
  // The camera pass drew into `radiance` and `translucent` as render targets; the image loads must see it.
  glMemoryBarrier(GL_FRAMEBUFFER_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  program_.use();
  program_.set("uFirst", first ? 1 : 0);
  program_.set("uShare", 1.0f / static_cast<float>(frames_));
  program_.set("uWeight", static_cast<float>(weight));
  glBindImageTexture(0, radiance.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
  glBindImageTexture(1, translucent.id(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
  glBindImageTexture(2, rest_.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
  glBindImageTexture(3, translucentSum_.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
  glBindImageTexture(4, translucentShare_.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32F);
  glDispatchCompute((static_cast<GLuint>(radiance.width()) + kGroup - 1) / kGroup,
                    (static_cast<GLuint>(radiance.height()) + kGroup - 1) / kGroup, 1);
  // Later readers sample the texture, read it back or draw over it.
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT |
                  GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  gpu::unbindComputeState(5, 0);
}

}  // namespace tallow::sss
