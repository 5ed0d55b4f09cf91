#include "sss/maps/layered_program.h"

#include <atomic>

#include "gpu/gl_limits.h"

namespace tallow::sss {
namespace {
std::atomic<bool> allowed{true};
}  // namespace

bool layerInVertexShader() { return allowed.load() && gpu::glLimits().layerInVertexShader; }

void allowLayerInVertexShader(bool allow) { allowed.store(allow); }

gpu::ProgramDesc layeredProgram(const std::string& fragment) {
  if (layerInVertexShader())
    return {{{GL_VERTEX_SHADER, "maps/layered.vert"}, {GL_FRAGMENT_SHADER, fragment}}, {"TALLOW_LAYER_IN_VERTEX"}};
  return {{{GL_VERTEX_SHADER, "maps/layered.vert"},
           {GL_GEOMETRY_SHADER, "maps/layered.geom"},
           {GL_FRAGMENT_SHADER, fragment}}};
}

}  // namespace tallow::sss
