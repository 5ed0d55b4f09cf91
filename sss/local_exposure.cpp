#include "sss/local_exposure.h"

#include <algorithm>
#include <cmath>

namespace tallow::sss {

namespace {
constexpr GLuint kGroup = 8;  // local_exposure.comp's local size

GLuint groups(int n) { return (static_cast<GLuint>(n) + kGroup - 1) / kGroup; }

/// Grid cells along a side of n pixels.
int cells(int n, int cell) { return (n + cell - 1) / cell; }
}  // namespace

LocalExposure::LocalExposure(const gpu::ShaderLibrary& shaders)
    : program_(shaders, {{{GL_COMPUTE_SHADER, "camera/local_exposure.comp"}}}) {}

int LocalExposure::cellFor(int width, int height) {
  return std::max(2, static_cast<int>(std::lround(0.02 * std::max(width, height))));
}

std::size_t LocalExposure::bytesFor(int width, int height) {
  const int s = cellFor(width, height);
  return 2 * gpu::Texture::bytesFor(GL_TEXTURE_3D, GL_RG32F, cells(width, s), cells(height, s), kBins, 1) +
         gpu::Texture::bytesFor(GL_TEXTURE_2D, GL_RGBA32F, width, height, 1, 1) +
         gpu::Texture::bytesFor(GL_TEXTURE_2D, GL_R32F, width, height, 1, 1);
}

void LocalExposure::apply(const gpu::Texture& picture, float strength, float exposureScale,
                          const gpu::Texture* coverage) {
  const int w = picture.width(), h = picture.height(), s = cellFor(w, h);
  const int gw = cells(w, s), gh = cells(h, s);
  if (!output_.id() || output_.width() != w || output_.height() != h) {
    for (gpu::Texture& g : grid_) {
      g = gpu::Texture::create3D(GL_RG32F, gw, gh, kBins);
      g.setFilter(GL_LINEAR, GL_LINEAR);
      for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
        glTextureParameteri(g.id(), wrap, GL_CLAMP_TO_EDGE);
    }
    output_ = gpu::Texture::create2D(GL_RGBA32F, w, h);
    output_.setFilter(GL_NEAREST, GL_NEAREST);
    gain_ = gpu::Texture::create2D(GL_R32F, w, h);
    gain_.setFilter(GL_NEAREST, GL_NEAREST);
  }
  // The camera pass (the still's average, the glare) wrote the picture; the steps below read it.
  glMemoryBarrier(GL_FRAMEBUFFER_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  program_.use();
  program_.set("uPicture", 0);
  program_.set("uGrid", 1);
  program_.set("uCell", s);
  program_.set("uExposureScale", exposureScale);
  program_.set("uStrength", strength);
  picture.bind(0);
  // Step 0 splats into grid 0; steps 1-3 blur 0 → 1 → 0 → 1; step 4 slices grid 1.
  for (int step = 0; step <= 3; ++step) {
    const gpu::Texture& out = grid_[step % 2 == 0 ? 0 : 1];
    if (step > 0) grid_[step % 2 == 0 ? 1 : 0].bind(1);
    program_.set("uStep", step);
    glBindImageTexture(0, out.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RG32F);
    glDispatchCompute(groups(gw), groups(gh), 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  }
  // Step 4 slices grid 1 into each pixel's gain; step 5 applies the gains, blended on edges.
  program_.set("uGain", 2);
  program_.set("uStep", 4);
  grid_[1].bind(1);
  glBindImageTexture(2, gain_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
  glDispatchCompute(groups(w), groups(h), 1);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  program_.set("uStep", 5);
  program_.set("uCoverage", 3);
  program_.set("uCoverageAlpha", coverage ? 1 : 0);
  if (coverage) coverage->bind(3);
  gain_.bind(2);
  glBindImageTexture(1, output_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  glDispatchCompute(groups(w), groups(h), 1);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
  gpu::unbindComputeState(3, 4);
}

}  // namespace tallow::sss
