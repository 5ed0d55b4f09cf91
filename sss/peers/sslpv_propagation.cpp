#include "sss/peers/sslpv_propagation.h"

#include "sss/peers/sslpv_math.h"

namespace tallow::sss {
namespace {

constexpr GLuint kTargetImage = 0;        // 0, 1, 2: this step's result per band
constexpr GLuint kAccumulationImage = 3;  // 3, 4, 5
constexpr GLuint kSourceUnit = 0;         // 0, 1, 2: the step before
constexpr GLuint kExtinctionUnit = 3, kScatteringUnit = 4, kAnisotropyUnit = 5;

gpu::Texture coefficientGrid(int size) {
  gpu::Texture t = gpu::Texture::create3D(GL_RGBA32F, size, size, size);
  t.setFilter(GL_LINEAR, GL_LINEAR);  // the camera pass reads the accumulation trilinearly
  t.setWrap(GL_CLAMP_TO_EDGE);
  return t;
}

}  // namespace

SslpvPropagation::SslpvPropagation(const gpu::ShaderLibrary& shaders)
    : program_(shaders, {{{GL_COMPUTE_SHADER, "peers/sslpv/propagate.comp"}}}), matrices_(sslpvPropagationMatrices()) {
  program_.set("uPropagation", matrices_.data(), 6);
}

void SslpvPropagation::resize(int size) {
  if (size_ == size) return;
  size_ = size;
  for (auto& set : grids_)
    for (auto& t : set) t = coefficientGrid(size);
  for (auto& t : accumulation_) t = coefficientGrid(size);
  current_ = 0;
}

void SslpvPropagation::clear() {
  const glm::vec4 zero(0.0f);
  for (const auto& t : grids_[current_]) glClearTexImage(t.id(), 0, GL_RGBA, GL_FLOAT, &zero.x);
  for (const auto& t : accumulation_) glClearTexImage(t.id(), 0, GL_RGBA, GL_FLOAT, &zero.x);
}

void SslpvPropagation::propagate(int steps, int skip, float cellMm, const SslpvMedium& medium) {
  gpu::Program& p = program_;
  p.use();
  p.set("uSize", size_);
  p.set("uCellMm", cellMm);
  p.set("uSourceR", static_cast<int>(kSourceUnit));
  p.set("uSourceG", static_cast<int>(kSourceUnit + 1));
  p.set("uSourceB", static_cast<int>(kSourceUnit + 2));
  p.set("uExtinction", static_cast<int>(kExtinctionUnit));
  p.set("uScattering", static_cast<int>(kScatteringUnit));
  p.set("uAnisotropy", static_cast<int>(kAnisotropyUnit));
  medium.extinction().bind(kExtinctionUnit);
  medium.scattering().bind(kScatteringUnit);
  medium.anisotropy().bind(kAnisotropyUnit);
  for (GLuint c = 0; c < 3; ++c)
    glBindImageTexture(kAccumulationImage + c, accumulation_[c].id(), 0, GL_TRUE, 0, GL_READ_WRITE, GL_RGBA32F);
  const auto groups = static_cast<GLuint>((size_ + 3) / 4);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
  for (int step = 1; step <= steps; ++step) {
    const auto& source = grids_[current_];
    const auto& target = grids_[1 - current_];
    for (GLuint c = 0; c < 3; ++c) {
      source[c].bind(kSourceUnit + c);
      glBindImageTexture(kTargetImage + c, target[c].id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    }
    p.set("uAccumulate", step > skip ? 1 : 0);
    glDispatchCompute(groups, groups, groups);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    current_ = 1 - current_;
  }
  for (GLuint unit = 0; unit < 6; ++unit) {
    glBindImageTexture(unit, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
    glBindTextureUnit(unit, 0);
  }
  glUseProgram(0);
}

std::size_t SslpvPropagation::bytes() const {
  std::size_t total = 0;
  for (const auto& set : grids_)
    for (const auto& t : set) total += t.bytes();
  for (const auto& t : accumulation_) total += t.bytes();
  return total;
}

void SslpvPropagation::upload(int band, const std::vector<glm::vec4>& cells) {
  const gpu::Texture& t = grids_[current_][static_cast<std::size_t>(band)];
  glTextureSubImage3D(t.id(), 0, 0, 0, 0, size_, size_, size_, GL_RGBA, GL_FLOAT, cells.data());
}

std::vector<glm::vec4> SslpvPropagation::download(const gpu::Texture& grid) const {
  std::vector<glm::vec4> cells(static_cast<std::size_t>(size_) * size_ * size_);
  glGetTextureImage(grid.id(), 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(cells.size() * sizeof(glm::vec4)),
                    cells.data());
  return cells;
}

}  // namespace tallow::sss
