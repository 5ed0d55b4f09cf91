#include "gpu/gl_context.h"

#include <glad/gl.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "gpu/gl_context_backends.h"
#include "gpu/gl_limits.h"

#if defined(__SANITIZE_ADDRESS__)
#include <dlfcn.h>
#endif

namespace tallow::gpu {

GlBackend parseGlBackend(std::string_view name) {
  if (name == "glfw") return GlBackend::Glfw;
  if (name == "osmesa") return GlBackend::OsMesa;
  if (name == "egl") return GlBackend::Egl;
  throw std::invalid_argument("unknown GL backend \"" + std::string(name) + "\" (glfw, osmesa, egl)");
}

std::string_view glBackendName(GlBackend backend) {
  switch (backend) {
    case GlBackend::Glfw: return "glfw";
    case GlBackend::OsMesa: return "osmesa";
    case GlBackend::Egl: return "egl";
  }
  return "?";
}

namespace {
/// Under AddressSanitizer only: glvnd unloads the vendor driver when the display is terminated,
/// after which LeakSanitizer can neither name nor suppress the allocations the driver never
/// freed (tests/lsan.supp). Pinning the drivers keeps their symbols for the report.
void pinDriversForLeakReports() {
#if defined(__SANITIZE_ADDRESS__)
  for (const char* lib : {"libEGL_mesa.so.0", "libGLX_mesa.so.0", "libEGL_nvidia.so.0", "libGLX_nvidia.so.0",
                          "/usr/lib/x86_64-linux-gnu/dri/swrast_dri.so"})
    dlopen(lib, RTLD_NOW | RTLD_NODELETE);
#endif
}
}  // namespace

std::unique_ptr<GlContext> GlContext::create(const ContextOptions& options) {
  pinDriversForLeakReports();
  switch (options.backend) {
    case GlBackend::Glfw: return detail::createGlfwContext(options);
    case GlBackend::OsMesa: return detail::createOsMesaContext(options);
    case GlBackend::Egl: return detail::createEglContext(options);
  }
  throw ContextError("unknown GL backend");
}

std::unique_ptr<GlContext> GlContext::createShared() const {
  throw ContextError(std::string(glBackendName(backend())) + ": no shared context for a render thread (a window's only)");
}

namespace {

const char* str(GLenum name) {
  const auto* s = reinterpret_cast<const char*>(glGetString(name));
  return s ? s : "";
}

void GLAD_API_PTR debugCallback(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei,
                                const GLchar* message, const void*) {
  (void)source;
  if (severity == GL_DEBUG_SEVERITY_NOTIFICATION) return;
  const char* kind = type == GL_DEBUG_TYPE_ERROR ? "error" : type == GL_DEBUG_TYPE_PERFORMANCE ? "performance" : "debug";
  std::fprintf(stderr, "gl %s %u: %s\n", kind, id, message);
}

}  // namespace

void GlContext::loadGl(void* (*getProcAddress)(const char*), std::string_view backendName, bool debugOutput) {
  const int version = gladLoadGL(reinterpret_cast<GLADloadfunc>(getProcAddress));
  if (version == 0) throw ContextError(std::string(backendName) + ": could not load OpenGL functions");
  info_.vendor = str(GL_VENDOR);
  info_.renderer = str(GL_RENDERER);
  info_.version = str(GL_VERSION);
  info_.glsl = str(GL_SHADING_LANGUAGE_VERSION);
  info_.major = GLAD_VERSION_MAJOR(version);
  info_.minor = GLAD_VERSION_MINOR(version);
  if (info_.major * 10 + info_.minor < 45) {
    throw ContextError("OpenGL 4.5 core is required, but " + std::string(backendName) + " offers " +
                       info_.version + " (" + info_.renderer + ")");
  }
  readGlLimits();
  if (debugOutput) {
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(debugCallback, nullptr);
  } else if (const char* errors = std::getenv("TALLOW_GL_ERRORS"); errors && std::string_view(errors) == "1") {
    // Release builds too: GL errors only, reported asynchronously so that timings stay as they are.
    // The device bench sets it: a first run on an unfamiliar driver must not fail silently.
    glEnable(GL_DEBUG_OUTPUT);
    glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, nullptr, GL_FALSE);
    glDebugMessageControl(GL_DONT_CARE, GL_DEBUG_TYPE_ERROR, GL_DONT_CARE, 0, nullptr, GL_TRUE);
    glDebugMessageCallback(debugCallback, nullptr);
  }
}

}  // namespace tallow::gpu

namespace tallow::gpu::detail {

std::string describeFallbackVersion(void* (*getProcAddress)(const char*)) {
  using GetString = const unsigned char* (*)(unsigned int);
  auto getString = reinterpret_cast<GetString>(getProcAddress("glGetString"));
  if (!getString) return "no usable OpenGL";
  const auto* version = getString(GL_VERSION);
  const auto* renderer = getString(GL_RENDERER);
  const std::string text = version ? reinterpret_cast<const char*>(version) : "?";
  // "4.5 (Compatibility Profile) Mesa …" names a version that is there, but not as a core profile.
  const bool compatibility = text.find("Compatibility") != std::string::npos;
  return std::string(compatibility ? "no core profile of 4.5, only a compatibility context: " : "") + text + " (" +
         (renderer ? reinterpret_cast<const char*>(renderer) : "?") + ")";
}

}  // namespace tallow::gpu::detail
