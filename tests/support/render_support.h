#pragma once
// Renders a preset headless in-process, exactly as `tallow capture` does, for image tests.
#include <memory>
#include <string>
#include <vector>

#include "app/config/setup.h"
#include "gpu/gl_context.h"
#include "gpu/image.h"
#include "gpu/shader_library.h"
#include "sss/renderer.h"

namespace tallow::test {

struct RenderResult {
  gpu::Image image;  ///< linear radiance, top row first
  sss::FrameTimings timings;
  gpu::GlInfo gl;
};

/// `preset` is a name in presets/ or a path; `sets` are "key=value" as for --set.
RenderResult renderPreset(const std::string& preset, const std::vector<std::string>& sets = {},
                          gpu::GlBackend backend = gpu::GlBackend::OsMesa);

/// A preset loaded with `sets`, its hidden GL context and renderer, for tests that render several
/// frames (progressive accumulation, animation) or read the renderer's state.
class PresetSession {
 public:
  explicit PresetSession(const std::string& preset, const std::vector<std::string>& sets = {},
                         gpu::GlBackend backend = gpu::GlBackend::OsMesa);
  sss::Scene& scene() { return loaded_.config.scene; }
  const sss::Scene& scene() const { return loaded_.config.scene; }
  sss::RenderSettings& settings() { return loaded_.config.render; }
  const sss::RenderSettings& settings() const { return loaded_.config.render; }
  /// The renderer, its context made current (a test may hold several sessions; GL names are per
  /// context, and a session used in another's context reads that one's objects).
  sss::Renderer& renderer() {
    context_->makeCurrent();
    return *renderer_;
  }
  const sss::Renderer& renderer() const {
    context_->makeCurrent();
    return *renderer_;
  }
  /// The library the renderer's programs come from, for a test's own GPU passes in this context.
  const gpu::ShaderLibrary& shaders() const { return shaders_; }
  /// Renders the frame at time t; returns its linear radiance.
  gpu::Image render(double timeS = 0.0, sss::FrameTimings* timings = nullptr);
  /// Renders the frame at time t without reading anything back; returns its timings as the
  /// renderer gives them (GPU times not resolved).
  sss::FrameTimings renderFrame(double timeS = 0.0);

 private:
  app::LoadedScene loaded_;
  std::unique_ptr<gpu::GlContext> context_;
  gpu::ShaderLibrary shaders_;
  std::unique_ptr<sss::Renderer> renderer_;
};

/// Mean of a band over the centre square of the image (half its width and height): the part of a
/// slab test's picture far from the slab's edges.
double centreMean(const gpu::Image& image, int band);

/// Path of a test scene in tests/data/.
std::string testScene(const std::string& name);

/// A field preset's settings for the GPU field tests: 64x48, a coarse lattice of `res` cells, six
/// small maps and one frame, with the given vertex placement (field.placement).
std::vector<std::string> smallFieldSets(int res, const std::string& placement = "qef");

}  // namespace tallow::test
