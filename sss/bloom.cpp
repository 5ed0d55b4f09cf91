#include "sss/bloom.h"

#include <algorithm>
#include <bit>

namespace tallow::sss {

namespace {
/// Levels of the full mip chain of a width × height picture.
int pyramidLevels(int width, int height) {
  return static_cast<int>(std::bit_width(static_cast<unsigned>(std::max(width, height))));
}
}  // namespace

Bloom::Bloom(const gpu::ShaderLibrary& shaders) : program_(shaders, {{{GL_COMPUTE_SHADER, "camera/bloom.comp"}}}) {}

std::size_t Bloom::bytesFor(int width, int height) {
  return gpu::Texture::bytesFor(GL_TEXTURE_2D, GL_RGBA32F, width, height, 1, pyramidLevels(width, height)) +
         gpu::Texture::bytesFor(GL_TEXTURE_2D, GL_RGBA32F, width, height, 1, 1);
}

void Bloom::apply(const gpu::Texture& radiance, float share, float exposureScale, const gpu::Texture* coverage) {
  const int w = radiance.width(), h = radiance.height();
  if (!output_.id() || output_.width() != w || output_.height() != h) {
    pyramid_ = gpu::Texture::create2D(GL_RGBA32F, w, h, pyramidLevels(w, h));
    pyramid_.setFilter(GL_LINEAR_MIPMAP_NEAREST, GL_LINEAR);
    glTextureParameteri(pyramid_.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(pyramid_.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    output_ = gpu::Texture::create2D(GL_RGBA32F, w, h);
    output_.setFilter(GL_NEAREST, GL_NEAREST);
  }
  // The camera pass (and the still's average) wrote the picture; the passes below read it.
  glMemoryBarrier(GL_FRAMEBUFFER_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  constexpr GLuint kGroup = 16;  // bloom.comp's local size
  const GLuint groupsX = (static_cast<GLuint>(w) + kGroup - 1) / kGroup, groupsY = (static_cast<GLuint>(h) + kGroup - 1) / kGroup;
  program_.use();
  program_.set("uRadiance", 0);
  program_.set("uBright", 1);
  program_.set("uLevels", std::min(kLevels, pyramid_.levels() - 1));
  program_.set("uShare", share);
  program_.set("uExposureScale", exposureScale);
  program_.set("uCoverage", 2);
  program_.set("uCoverageAlpha", coverage ? 1 : 0);
  radiance.bind(0);
  if (coverage) coverage->bind(2);
  // Step 0: the light above white into level 0 of the chain; then its box-filtered levels.
  program_.set("uStep", 0);
  glBindImageTexture(1, pyramid_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  glDispatchCompute(groupsX, groupsY, 1);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
  glGenerateTextureMipmap(pyramid_.id());  // each level keeps the bright part's mean
  // Step 1: the picture with a share of its bright light spread by the PSF (the program is still bound).
  program_.set("uStep", 1);
  pyramid_.bind(1);
  glBindImageTexture(0, output_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  glDispatchCompute(groupsX, groupsY, 1);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
  gpu::unbindComputeState(2, 3);
}

}  // namespace tallow::sss
