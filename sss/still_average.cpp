#include "sss/still_average.h"

#include <stdexcept>

namespace tallow::sss {

StillAverage::StillAverage(const gpu::ShaderLibrary& shaders)
    : program_(shaders, {{{GL_COMPUTE_SHADER, "camera/still_average.comp"}}}) {}

void StillAverage::add(const gpu::Texture& radiance, double weight, bool first) {
  if (!(weight > 0.0)) throw std::logic_error("still average: a frame's weight must be positive");
  if (!history_.id() || history_.width() != radiance.width() || history_.height() != radiance.height()) {
    history_ = gpu::Texture::create2D(GL_RGBA32F, radiance.width(), radiance.height());
    first = true;
  }
  weightSum_ = first ? weight : weightSum_ + weight;
  frames_ = first ? 1 : frames_ + 1;
  constexpr GLuint kGroup = 16;  // still_average.comp's local size
  // The camera pass drew into `radiance` as a render target; the image loads must see it.
  glMemoryBarrier(GL_FRAMEBUFFER_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  program_.use();
  program_.set("uShare", static_cast<float>(weight / weightSum_));
  glBindImageTexture(0, radiance.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
  glBindImageTexture(1, history_.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
  glDispatchCompute((static_cast<GLuint>(radiance.width()) + kGroup - 1) / kGroup,
                    (static_cast<GLuint>(radiance.height()) + kGroup - 1) / kGroup, 1);
  // Later readers sample the texture, read it back or draw over it.
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT |
                  GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  gpu::unbindComputeState(2, 0);
}

}  // namespace tallow::sss
