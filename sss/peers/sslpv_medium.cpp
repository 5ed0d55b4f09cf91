#include "sss/peers/sslpv_medium.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <stdexcept>

#include "sss/maps/layered_program.h"
#include "sss/maps/radiosity_maps.h"

namespace tallow::sss {
namespace {

constexpr GLuint kParityImage = 0;
constexpr GLuint kExtinctionImage = 1, kScatteringImage = 2, kAnisotropyImage = 3;

/// Orthographic view of the grid's cube along `axis`: NDC x, y from the two other axes (cyclic
/// order), window depth 0 … 1 across the cube along `axis` (shaders/peers/sslpv/voxelize.frag).
glm::mat4 axisView(const SslpvGrid& grid, int axis) {
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  const float k = 2.0f / grid.side();
  glm::mat4 m(0.0f);
  m[u][0] = k;
  m[3][0] = -k * grid.origin[u] - 1.0f;
  m[v][1] = k;
  m[3][1] = -k * grid.origin[v] - 1.0f;
  m[axis][2] = k;
  m[3][2] = -k * grid.origin[axis] - 1.0f;
  m[3][3] = 1.0f;
  return m;
}

/// The object's frame without scale (metres): x_object = Rᵀ (x − position), R as
/// SceneGeometry::modelMatrix rotates (Z · Y · X).
glm::mat4 worldToObject(const Transform& t) {
  glm::mat4 rotation(1.0f);
  rotation = glm::rotate(rotation, glm::radians(t.rotationDeg.z), glm::vec3(0, 0, 1));
  rotation = glm::rotate(rotation, glm::radians(t.rotationDeg.y), glm::vec3(0, 1, 0));
  rotation = glm::rotate(rotation, glm::radians(t.rotationDeg.x), glm::vec3(1, 0, 0));
  return glm::transpose(rotation) * glm::translate(glm::mat4(1.0f), -t.position);
}

gpu::Texture gridTexture(int size) {
  gpu::Texture t = gpu::Texture::create3D(GL_RGBA32F, size, size, size);
  t.setFilter(GL_LINEAR, GL_LINEAR);  // the camera pass interpolates the medium flag (peers/sslpv/lookup.glsl)
  t.setWrap(GL_CLAMP_TO_EDGE);
  return t;
}

}  // namespace

SslpvMedium::SslpvMedium(const gpu::ShaderLibrary& shaders)
    : voxelize_(shaders, layeredProgram("peers/sslpv/voxelize.frag")),
      medium_(shaders, {{{GL_COMPUTE_SHADER, "peers/sslpv/medium.comp"}}}) {}

void SslpvMedium::ensureTextures(int size) {
  if (extinction_.id() && extinction_.width() == size) return;
  extinction_ = gridTexture(size);
  scattering_ = gridTexture(size);
  anisotropy_ = gridTexture(size);
}

void SslpvMedium::fillUniform(int size, const glm::vec3& sigmaT, const glm::vec3& sigmaPrime, const glm::vec3& g) {
  ensureTextures(size);
  const glm::vec4 e(sigmaT, 1.0f), s(sigmaPrime, 1.0f), a(g, 0.0f);
  glClearTexImage(extinction_.id(), 0, GL_RGBA, GL_FLOAT, &e.x);
  glClearTexImage(scattering_.id(), 0, GL_RGBA, GL_FLOAT, &s.x);
  glClearTexImage(anisotropy_.id(), 0, GL_RGBA, GL_FLOAT, &a.x);
}

void SslpvMedium::build(const Scene& scene, const SceneGeometry& geometry, const std::vector<int>& slots,
                        const SslpvGrid& grid) {
  const int n = grid.size, samples = 2 * n, words = parityWords(n);
  const int slotCount = static_cast<int>(std::count_if(slots.begin(), slots.end(), [](int s) { return s >= 0; }));
  ensureTextures(n);
  const int layers = std::max(slotCount, 1) * 3 * words;
  if (!parity_.id() || parity_.width() != samples || parity_.depth() != layers) {
    parity_ = gpu::Texture::create2DArray(GL_R32UI, samples, samples, layers);
    parity_.setFilter(GL_NEAREST, GL_NEAREST);
  }
  const GLuint zero = 0;
  glClearTexImage(parity_.id(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);

  // 1. Parity along the three axes: one instanced layered draw per object, no attachments.
  const std::vector<glm::mat4> views = {axisView(grid, 0), axisView(grid, 1), axisView(grid, 2)};
  axisViews_ = gpu::Buffer(views.size() * sizeof(glm::mat4), views.data());
  gpu::Framebuffer fb;
  glNamedFramebufferParameteri(fb.id(), GL_FRAMEBUFFER_DEFAULT_WIDTH, samples);
  glNamedFramebufferParameteri(fb.id(), GL_FRAMEBUFFER_DEFAULT_HEIGHT, samples);
  glNamedFramebufferParameteri(fb.id(), GL_FRAMEBUFFER_DEFAULT_LAYERS, 3);
  fb.setDrawBuffers(0);
  fb.checkComplete("SSLPV voxelisation");
  fb.bind();
  glViewport(0, 0, samples, samples);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  glEnable(GL_DEPTH_CLAMP);  // a surface in front of the cube still flips its whole column
  voxelize_.use();
  voxelize_.set("uSamples", samples);
  voxelize_.set("uWords", words);
  glBindImageTexture(kParityImage, parity_.id(), 0, GL_TRUE, 0, GL_READ_WRITE, GL_R32UI);
  drawTranslucentLayered(voxelize_, geometry, slots, axisViews_, 3);
  glDisable(GL_DEPTH_CLAMP);
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);

  // 2. The material per cell.
  std::vector<glm::vec3> sigmaA(kMaxTranslucentObjects, glm::vec3(0.0f)), sigmaS = sigmaA, g = sigmaA,
                         innerA = sigmaA, innerS = sigmaA, innerG = sigmaA, axis = sigmaA;
  std::vector<glm::mat4> toObject(kMaxTranslucentObjects, glm::mat4(1.0f));
  std::vector<glm::vec4> shape(kMaxTranslucentObjects, glm::vec4(1.0f, 0.0f, 0.0f, 0.0f));
  std::vector<GLint> volume(kMaxTranslucentObjects, 0);
  std::vector<GLuint> seed(kMaxTranslucentObjects, 0u);
  for (std::size_t i = 0; i < scene.objects.size() && i < slots.size(); ++i) {
    const int slot = slots[i];
    if (slot < 0) continue;
    const auto k = static_cast<std::size_t>(slot);
    const SceneObject& o = scene.objects[i];
    sigmaA[k] = o.material.sigma_a;
    sigmaS[k] = o.material.sigma_s;
    g[k] = o.material.g;
    toObject[k] = worldToObject(o.transform);
    if (o.volume) {
      const MaterialVolume& v = *o.volume;
      volume[k] = 1;
      innerA[k] = v.material.sigma_a;
      innerS[k] = v.material.sigma_s;
      innerG[k] = v.material.g;
      axis[k] = v.axis;
      shape[k] = glm::vec4(v.period, v.fraction, v.turbulence, 0.0f);
      seed[k] = v.seed;
    }
  }
  gpu::Program& p = medium_;
  p.use();
  p.set("uSlotCount", slotCount);
  p.set("uSize", n);
  p.set("uWords", words);
  p.set("uOrigin", grid.origin);
  p.set("uCell", grid.cell);
  p.set("uCellMm", grid.cellMm());
  p.set("uSigmaA", sigmaA.data(), kMaxTranslucentObjects);
  p.set("uSigmaS", sigmaS.data(), kMaxTranslucentObjects);
  p.set("uG", g.data(), kMaxTranslucentObjects);
  p.set("uInnerSigmaA", innerA.data(), kMaxTranslucentObjects);
  p.set("uInnerSigmaS", innerS.data(), kMaxTranslucentObjects);
  p.set("uInnerG", innerG.data(), kMaxTranslucentObjects);
  p.set("uVolumeAxis", axis.data(), kMaxTranslucentObjects);
  p.set("uVolumeShape", shape.data(), kMaxTranslucentObjects);
  p.set("uWorldToObject", toObject.data(), kMaxTranslucentObjects);
  glProgramUniform1iv(p.id(), p.location("uVolume"), kMaxTranslucentObjects, volume.data());
  glProgramUniform1uiv(p.id(), p.location("uVolumeSeed"), kMaxTranslucentObjects, seed.data());
  glBindImageTexture(kParityImage, parity_.id(), 0, GL_TRUE, 0, GL_READ_ONLY, GL_R32UI);
  glBindImageTexture(kExtinctionImage, extinction_.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  glBindImageTexture(kScatteringImage, scattering_.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  glBindImageTexture(kAnisotropyImage, anisotropy_.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  const auto groups = static_cast<GLuint>((n + 3) / 4);
  glDispatchCompute(groups, groups, groups);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  for (GLuint unit : {kParityImage, kExtinctionImage, kScatteringImage, kAnisotropyImage})
    glBindImageTexture(unit, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32UI);
  glBindVertexArray(0);
  glUseProgram(0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

std::size_t SslpvMedium::bytes() const {
  return parity_.bytes() + extinction_.bytes() + scattering_.bytes() + anisotropy_.bytes();
}

}  // namespace tallow::sss
