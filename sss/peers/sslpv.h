#pragma once
// Subsurface light propagation volumes (Børlum, Christensen, Kjeldsen, Mikkelsen, Noe, Rimestad and
// Mosegaard 2011, "the paper"; docs/sslpv.md): the peer method `method=sslpv`. Per frame, when the
// scene changed:
//   sslpv.voxelize      the medium grid (sss/peers/sslpv_medium.h): an N³ LPV grid fitted to the
//                       translucent objects, which cells are inside them and their σ_t, σ'_s, g;
//   sslpv.light_gbuffer the lights' G-buffers at sslpv.inject_size (the radiosity maps' step 1,
//                       the paper's RSMs: position, normal, translucent tag);
//   sslpv.inject        Eq. 1 per texel into the propagation grid (sss/peers/sslpv_injection.h);
//   sslpv.propagate     sslpv.steps steps of §3.2/§4 into the accumulation grid
//                       (sss/peers/sslpv_propagation.h);
// and every frame the camera pass reads the accumulation grid (Eqs. 6–7, shaders/peers/sslpv/lookup.glsl).
// Everything is deterministic: with the same scene and settings a recomputation gives the same
// grids, so the four passes run only when their inputs changed (sss/peers/sslpv_method.h).
#include <memory>
#include <string>
#include <vector>

#include "gpu/program.h"
#include "gpu/shader_library.h"
#include "sss/maps/radiosity_maps.h"
#include "sss/peers/sslpv_injection.h"
#include "sss/peers/sslpv_math.h"
#include "sss/peers/sslpv_medium.h"
#include "sss/peers/sslpv_propagation.h"
#include "sss/render_settings.h"
#include "sss/scene.h"
#include "sss/scene_geometry.h"

namespace tallow::sss {

/// GPU memory the SSLPV grids may take before checkLimits refuses sslpv.grid.
inline constexpr std::size_t kSslpvMemoryBudget = std::size_t{1} << 30;

class Sslpv {
 public:
  explicit Sslpv(const gpu::ShaderLibrary& shaders);

  /// True when `settings` selects SSLPV and the scene has a translucent object.
  static bool applies(const Scene& scene, const RenderSettings& settings);
  /// Throws std::invalid_argument with one line when the grid, its memory (the grids and the
  /// voxelisation's parity images, against kSslpvMemoryBudget) or the injection exceed this GPU.
  static void checkLimits(const Scene& scene, const RenderSettings& settings);
  /// GPU bytes of the grids for `size`³ cells and `objects` translucent objects.
  static std::size_t gridBytes(int size, int objects);

  /// The plan's reasons for the four passes.
  static std::string describeVoxelize(const Scene& scene, const RenderSettings& settings);
  static std::string describeLightGBuffer(const Scene& scene, const RenderSettings& settings);
  static std::string describeInject(const RenderSettings& settings);
  static std::string describePropagate(const RenderSettings& settings);

  void voxelize(const Scene& scene, const RenderSettings& settings, const SceneGeometry& geometry);
  void renderLightGBuffers(const Scene& scene, const RenderSettings& settings, const SceneGeometry& geometry);
  void inject(const Scene& scene, const RenderSettings& settings);
  void propagate(const RenderSettings& settings);

  /// Everything shaders/peers/sslpv/lookup.glsl reads, the grids on units firstUnit … + 3.
  void setLookupUniforms(gpu::Program& program, const RenderSettings& settings, GLuint firstUnit) const;
  /// The look-up's samplers on their own units firstUnit … + 3 (unused).
  static void setLookupOff(gpu::Program& program, GLuint firstUnit);

  const SslpvGrid& grid() const { return grid_; }
  const SslpvMedium& medium() const { return medium_; }
  const SslpvPropagation& propagation() const { return propagation_; }
  std::size_t bytes() const;

 private:
  /// The light G-buffers' settings: sss.light_map_size = sslpv.inject_size, never automatic.
  static RenderSettings gbufferSettings(const RenderSettings& settings);

  RadiosityMaps gbuffers_;  ///< only its step 1, the lights' G-buffers
  SslpvMedium medium_;
  SslpvInjection injection_;
  SslpvPropagation propagation_;
  SslpvGrid grid_;
  std::vector<int> slots_;
};

}  // namespace tallow::sss
