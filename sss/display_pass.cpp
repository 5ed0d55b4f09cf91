#include "sss/display_pass.h"

#include <cmath>

namespace tallow::sss {

DisplayPass::DisplayPass(const gpu::ShaderLibrary& shaders)
    : program_(shaders, {{{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "display.frag"}}}) {}

void DisplayPass::render(const gpu::Texture& radiance, GLuint target, int width, int height,
                         const gpu::ToneMapSettings& toneMap, gpu::Dither dither) {
  program_.set("uDither", dither == gpu::Dither::On ? 1 : 0);
  program_.set("uRadiance", 0);
  program_.set("uExposureScale", std::exp2(toneMap.exposureEv));
  program_.set("uToneMap", static_cast<int>(toneMap.op));
  radiance.bind(0);
  glBindFramebuffer(GL_FRAMEBUFFER, target);
  glViewport(0, 0, width, height);
  glDisable(GL_DEPTH_TEST);
  program_.use();
  emptyVao_.bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  glUseProgram(0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

}  // namespace tallow::sss
