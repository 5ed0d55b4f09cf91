#pragma once
// SSLPV's injection (the paper's §3.1, Eq. 1): every texel of the light G-buffers (the radiosity
// maps' step 1, rendered at sslpv.inject_size: world position, normal and translucent tag) that
// sees a translucent object becomes a virtual point light of flux Φ_p (E × the texel's area for a
// directional light; I Δω_p with the cube face's texel solid angle for a point light),
// transmitted with the Fresnel factor T into a clamped cosine lobe about the refracted direction,
// projected on the SH (shaders/peers/sslpv/sh.glsl) and added to the LPV cell half a cell inside the
// surface from x_p. One point per texel, drawn with additive blending into the layers of the
// propagation grid (the LPV papers' injection by point rendering).
#include "gpu/gl_objects.h"
#include "gpu/program.h"
#include "gpu/shader_library.h"
#include "sss/maps/radiosity_maps.h"
#include "sss/peers/sslpv_math.h"

namespace tallow::sss {

class SslpvInjection {
 public:
  explicit SslpvInjection(const gpu::ShaderLibrary& shaders);
  /// Adds the lights' transmitted flux to `target` (one RGBA32F 3D texture per band) over `grid`.
  /// `gbuffers` holds this frame's light G-buffers for `scene` (renderLightGBuffers with
  /// `settings`, whose sss.light_map_size is the injection size).
  void inject(const Scene& scene, const RenderSettings& settings, const RadiosityMaps& gbuffers,
              const SslpvGrid& grid, const std::array<gpu::Texture, 3>& target);

 private:
  gpu::Program program_;
  gpu::VertexArray empty_;  ///< core profile: a draw needs a vertex array, even without attributes
};

}  // namespace tallow::sss
