#pragma once
// The visible flame of a burning candle (issue 16, point 5): for each point light that follows a
// candle field, an emissive teardrop standing on the wick, drawn into the camera target after the
// surface pass (depth-tested against it, added to what is behind: a flame is transparent) and
// nowhere else — not in the shadow maps, the light G-buffers or the radiosity maps, whose light is
// the point light's. Its radiance is the light's intensity over the flame's area, so that the
// drawn flame sends the camera the intensity the point light has.
#include <memory>
#include <string>

#include "gpu/gl_objects.h"
#include "gpu/program.h"
#include "sss/frame_passes.h"

namespace tallow::sss {

/// The flame's teardrop in the candle field's units (metres before the object's transform).
struct FlameShape {
  double height = 0.016;     ///< from its base, 1 mm below the wick's tip, to its tip
  double halfWidth = 0.0035;  ///< at its widest, a third of the way up
  /// The teardrop's area weighted by flame.frag's radiance profile: radiance = intensity / this
  /// sends the camera the light's intensity.
  double effectiveArea() const;
};

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
