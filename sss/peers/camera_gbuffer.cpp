#include "sss/peers/camera_gbuffer.h"

#include "sss/light_uniforms.h"

namespace tallow::sss {
namespace {

constexpr GLuint kDirectionalShadowUnit = 0, kPointShadowUnit = 1;

}  // namespace

gpu::Texture screenTexture(GLenum format, int width, int height) {
  gpu::Texture t = gpu::Texture::create2D(format, width, height);
  t.setFilter(GL_NEAREST, GL_NEAREST);
  t.setWrap(GL_CLAMP_TO_EDGE);
  return t;
}

std::size_t screenTextureBytes(GLenum format, int width, int height) {
  return gpu::Texture::bytesFor(GL_TEXTURE_2D, format, width, height, 1, 1);
}

CameraIrradianceGBuffer::CameraIrradianceGBuffer(const gpu::ShaderLibrary& shaders)
    : program_(shaders, {{{GL_VERTEX_SHADER, "surface.vert"}, {GL_FRAGMENT_SHADER, "peers/image_space/gbuffer.frag"}}}) {}

std::size_t CameraIrradianceGBuffer::bytesFor(int width, int height) {
  return 2 * screenTextureBytes(GL_RGBA32F, width, height) + screenTextureBytes(GL_RGBA16F, width, height) +
         screenTextureBytes(GL_DEPTH_COMPONENT32F, width, height);
}

std::size_t CameraIrradianceGBuffer::bytes() const {
  return position_.bytes() + normal_.bytes() + irradiance_.bytes() + depth_.bytes();
}

void CameraIrradianceGBuffer::render(const Scene& scene, const RenderSettings& settings, const SceneGeometry& geometry,
                                     const CameraView& camera, const ShadowPass& shadows) {
  slots_.assign(scene.objects.size(), -1);
  int slot = 0;
  for (std::size_t i = 0; i < scene.objects.size(); ++i)
    if (scene.objects[i].translucent) slots_[i] = slot++;
  if (!position_.id() || position_.width() != settings.width || position_.height() != settings.height) {
    position_ = screenTexture(GL_RGBA32F, settings.width, settings.height);
    normal_ = screenTexture(GL_RGBA16F, settings.width, settings.height);
    irradiance_ = screenTexture(GL_RGBA32F, settings.width, settings.height);
    depth_ = gpu::Texture::create2D(GL_DEPTH_COMPONENT32F, settings.width, settings.height);
    target_ = gpu::Framebuffer();
    target_.attachColor(0, position_);
    target_.attachColor(1, normal_);
    target_.attachColor(2, irradiance_);
    target_.attachDepth(depth_);
    target_.setDrawBuffers(3);
    target_.checkComplete("camera irradiance G-buffer");
  }
  const float zero[4] = {0, 0, 0, 0};
  const float one = 1.0f;
  for (GLint i = 0; i < 3; ++i) glClearNamedFramebufferfv(target_.id(), GL_COLOR, i, zero);
  glClearNamedFramebufferfv(target_.id(), GL_DEPTH, 0, &one);

  gpu::Program& p = program_;
  setLightUniforms(p, scene, settings, shadows, kDirectionalShadowUnit, kPointShadowUnit);
  setCameraUniforms(p, camera);
  target_.bind();
  glViewport(0, 0, settings.width, settings.height);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  p.use();
  for (const DrawItem& item : geometry.items()) {
    const SceneObject& object = scene.objects[static_cast<std::size_t>(item.objectIndex)];
    p.set("uModel", item.model);
    p.set("uNormalMatrix", item.normalMatrix);
    p.set("uSlot", slots_[static_cast<std::size_t>(item.objectIndex)]);
    p.set("uObjectEta", object.material.eta);
    item.draw();
  }
  // Back to the defaults (no GL state leaks between passes).
  glDisable(GL_DEPTH_TEST);
  glBindVertexArray(0);
  glUseProgram(0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

}  // namespace tallow::sss
