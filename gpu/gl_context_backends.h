#pragma once
// Factories of the three context backends, each in its own .cpp so that GLFW, OSMesa and EGL
// headers never meet.
#include <memory>

#include "gpu/gl_context.h"

namespace tallow::gpu::detail {

std::unique_ptr<GlContext> createGlfwContext(const ContextOptions& options);
std::unique_ptr<GlContext> createOsMesaContext(const ContextOptions& options);
std::unique_ptr<GlContext> createEglContext(const ContextOptions& options);

/// Tell the user what a backend offers when it refuses 4.5 core: a context of any version is made
/// current through `getProcAddress` and its GL_VERSION and GL_RENDERER returned as "X (Y)".
std::string describeFallbackVersion(void* (*getProcAddress)(const char*));

}  // namespace tallow::gpu::detail
