#include "sss/pass.h"

namespace tallow::sss {

void CameraTarget::ensure(int width, int height) {
  if (radiance.id() && radiance.width() == width && radiance.height() == height) return;
  radiance = gpu::Texture::create2D(GL_RGBA32F, width, height);
  radiance.setFilter(GL_NEAREST, GL_NEAREST);
  depth = gpu::Texture::create2D(GL_DEPTH_COMPONENT32F, width, height);
  coverage = gpu::Texture::create2D(GL_RGBA8, width, height);
  coverage.setFilter(GL_NEAREST, GL_NEAREST);
  coverageBins = gpu::Texture::create2D(GL_RG8UI, width, height);
  coverageBins.setFilter(GL_NEAREST, GL_NEAREST);
  translucent = gpu::Texture::create2D(GL_RGBA32F, width, height);
  translucent.setFilter(GL_NEAREST, GL_NEAREST);
  receiver = gpu::Texture::create2D(GL_RGBA32UI, width, height);
  receiver.setFilter(GL_NEAREST, GL_NEAREST);
  receiverAlbedo = gpu::Texture::create2D(GL_RGBA16F, width, height);
  receiverAlbedo.setFilter(GL_NEAREST, GL_NEAREST);
  framebuffer = gpu::Framebuffer();
  framebuffer.attachColor(0, radiance);
  framebuffer.attachColor(1, coverage);
  framebuffer.attachColor(2, coverageBins);
  framebuffer.attachColor(3, translucent);
  framebuffer.attachColor(4, receiver);
  framebuffer.attachColor(5, receiverAlbedo);
  framebuffer.attachDepth(depth);
  framebuffer.setDrawBuffers(6);
  framebuffer.checkComplete("camera target");
}

CameraView FrameContext::camera() const {
  const float aspect = static_cast<float>(settings().width) / static_cast<float>(settings().height);
  CameraView view = cameraView(scene().camera, aspect, geometry.worldBounds());
  if (cameraJitter != glm::vec2(0.0f)) {
    // The pixel looks through its centre plus the offset, in pixels with x right and y down as the
    // reference's pass does (sss/pixel_jitter.h): the image shifts by −x and +y in NDC (y up), 2 /
    // size per pixel, for perspective and orthographic cameras alike (the translation acts on clip
    // coordinates before the divide). A shift by +x sampled the x-mirror of the reference's points.
    glm::mat4 shift(1.0f);
    shift[3][0] = -2.0f * cameraJitter.x / static_cast<float>(settings().width);
    shift[3][1] = 2.0f * cameraJitter.y / static_cast<float>(settings().height);
    view.projection = shift * view.projection;
    view.viewProjection = view.projection * view.view;
  }
  return view;
}

}  // namespace tallow::sss
