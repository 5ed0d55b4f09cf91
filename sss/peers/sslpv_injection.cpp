#include "sss/peers/sslpv_injection.h"

namespace tallow::sss {

SslpvInjection::SslpvInjection(const gpu::ShaderLibrary& shaders)
    : program_(shaders, {{{GL_VERTEX_SHADER, "peers/sslpv/inject.vert"},
                          {GL_GEOMETRY_SHADER, "peers/sslpv/inject.geom"},
                          {GL_FRAGMENT_SHADER, "peers/sslpv/inject.frag"}}}) {}

void SslpvInjection::inject(const Scene& scene, const RenderSettings& settings, const RadiosityMaps& gbuffers,
                            const SslpvGrid& grid, const std::array<gpu::Texture, 3>& target) {
  int dir = 0, point = 0;
  for (const Light& l : scene.lights) (l.kind == LightKind::Directional ? dir : point)++;
  const int size = gbuffers.lightMapSize();
  const long long texels = static_cast<long long>(size) * size * (dir + 6LL * point);
  if (texels == 0) return;

  gpu::Program& p = program_;
  // The lights, their G-buffers on units 0 … 3 and the materials' η (the gather's uniforms).
  gbuffers.setGatherUniforms(p, scene, settings, 0, 0);
  p.set("uMapSize", size);
  p.set("uGridOrigin", grid.origin);
  p.set("uGridCell", grid.cell);
  p.set("uGridSize", grid.size);

  gpu::Framebuffer fb;
  for (int c = 0; c < 3; ++c) fb.attachColor(c, target[static_cast<std::size_t>(c)]);  // all layers
  fb.setDrawBuffers(3);
  fb.checkComplete("SSLPV injection");
  fb.bind();
  glViewport(0, 0, grid.size, grid.size);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glEnable(GL_BLEND);
  glBlendEquation(GL_FUNC_ADD);
  glBlendFunc(GL_ONE, GL_ONE);  // Σ_p I_p(ω) per cell (§3.1)
  p.use();
  empty_.bind();
  glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(texels));
  glDisable(GL_BLEND);
  glBindVertexArray(0);
  glUseProgram(0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  for (GLuint unit = 0; unit < 4; ++unit) glBindTextureUnit(unit, 0);
}

}  // namespace tallow::sss
