#pragma once
// The visible flame of a burning candle (issues 16 and 35): for each point light that follows a
// candle field, the flame of geometry/candle_flame.h — a soft-edged teardrop on the wick, its radiance
// shaders/flame/flame_profile.glsl (a blackbody profile, a dark cone, a blue base), bent by its sway
// and flickering with it — on a camera-facing sheet drawn into the camera target after the surface
// pass (depth-tested against it, added to what is behind: a flame is transparent) and nowhere else:
// not in the shadow maps, the light G-buffers or the radiosity maps, whose light is the point light's.
// The point light is the same emission (sceneAtTime): the flame's flux is the light's intensity, its
// emission centre the light's position.
#include <memory>
#include <string>

#include "gpu/gl_objects.h"
#include "gpu/program.h"
#include "sss/frame_passes.h"

namespace tallow::sss {

/// Lights drawn as flames: point lights that follow a candle field, when render.flame is on.
int flameCount(const FrameState& state);

class FlamePass final : public FramePass {
 public:
  std::string name() const override { return "flame"; }
  bool needed(const FrameState& state) const override { return flameCount(state) > 0; }
  std::string reason(const FrameState& state) const override;
  PassIo io(const FrameState& state) const override;
  void run(FrameContext& context, bool changed) override;

 private:
  std::unique_ptr<gpu::Program> program_;  ///< made on the first run (needs the GL context)
  std::unique_ptr<gpu::VertexArray> emptyVao_;  ///< the quad's corners come from gl_VertexID
};

}  // namespace tallow::sss
