#pragma once
// SSLPV's propagation (the paper's §3.2 and §4): the propagation grid, two copies per colour band
// used in turn as source and target (RGBA32F 3D textures of the four SH coefficients), and the
// accumulation grid. One compute dispatch per step: every cell gathers from its six neighbours
// c_d = Σ_s (Σ'_f M_{f,d←s}) · scatter(e^{−σ_t ΔX} c_s) (§3.2.1, Eq. 3, §4), a vacuum cell holds
// nothing (the light that leaves the objects is gone, docs/sslpv.md), and from step skip + 1 on
// the accumulation grid adds the step's result.
#include <glm/glm.hpp>

#include <array>
#include <vector>

#include "gpu/gl_objects.h"
#include "gpu/program.h"
#include "gpu/shader_library.h"
#include "sss/peers/sslpv_medium.h"

namespace tallow::sss {

class SslpvPropagation {
 public:
  explicit SslpvPropagation(const gpu::ShaderLibrary& shaders);

  /// Allocates the grids for size³ cells (keeps them when the size is unchanged).
  void resize(int size);
  /// Zeroes the propagation grid about to be injected into and the accumulation grid.
  void clear();
  /// The propagation grid of the current step, per band (the injection's target).
  const std::array<gpu::Texture, 3>& current() const { return grids_[current_]; }
  const std::array<gpu::Texture, 3>& accumulation() const { return accumulation_; }
  /// `steps` propagation steps through `medium` (cells of `cellMm` mm); steps 1 … skip are not
  /// accumulated (the paper's §4 skips 2).
  void propagate(int steps, int skip, float cellMm, const SslpvMedium& medium);

  int size() const { return size_; }
  std::size_t bytes() const;

  /// Tests: the current propagation grid or the accumulation grid of `band`, x fastest.
  void upload(int band, const std::vector<glm::vec4>& cells);
  std::vector<glm::vec4> download(const gpu::Texture& grid) const;

 private:
  gpu::Program program_;
  std::array<glm::mat4, 6> matrices_;
  std::array<std::array<gpu::Texture, 3>, 2> grids_;
  std::array<gpu::Texture, 3> accumulation_;
  int current_ = 0;
  int size_ = 0;
};

}  // namespace tallow::sss
