#pragma once
// Renders a preset headless in-process, exactly as `tallow capture` does, for image tests.
#include <string>
#include <vector>

#include "gpu/gl_context.h"
#include "gpu/image.h"
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

/// Path of a test scene in tests/data/.
std::string testScene(const std::string& name);

}  // namespace tallow::test
