// EGL without a window: the device platform first (NVIDIA's headless path; Mesa lists a software
// device too), then Mesa's surfaceless platform, then the default display. The context is made
// current with no surface (EGL_KHR_surfaceless_context); Tallow renders into its own FBOs.
#include <glad/gl.h>
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "gpu/gl_context_backends.h"

namespace tallow::gpu::detail {
namespace {

void* eglProc(const char* name) { return reinterpret_cast<void*>(eglGetProcAddress(name)); }

bool hasExtension(const char* list, const char* name) {
  if (!list) return false;
  const std::size_t n = std::strlen(name);
  for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n)
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

struct Candidate {
  EGLDisplay display;
  std::string platform;
};

std::vector<Candidate> candidateDisplays() {
  std::vector<Candidate> out;
  const char* clientExt = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  auto getPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (getPlatformDisplay && hasExtension(clientExt, "EGL_EXT_platform_device")) {
    auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    EGLint count = 0;
    if (queryDevices && queryDevices(0, nullptr, &count) && count > 0) {
      std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(count));
      queryDevices(count, devices.data(), &count);
      for (EGLint i = 0; i < count; ++i) {
        EGLDisplay d = getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[static_cast<std::size_t>(i)], nullptr);
        if (d != EGL_NO_DISPLAY) out.push_back({d, "device " + std::to_string(i)});
      }
    }
  }
  if (getPlatformDisplay && hasExtension(clientExt, "EGL_MESA_platform_surfaceless")) {
    EGLDisplay d = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (d != EGL_NO_DISPLAY) out.push_back({d, "surfaceless"});
  }
  if (EGLDisplay d = eglGetDisplay(EGL_DEFAULT_DISPLAY); d != EGL_NO_DISPLAY) out.push_back({d, "default"});
  return out;
}

class EglContext final : public GlContext {
 public:
  explicit EglContext(const ContextOptions& options) {
    std::string tried;
    std::string offer;
    for (const Candidate& c : candidateDisplays()) {
      if (tryDisplay(c, offer)) {
        makeCurrent();
        loadGl(eglProc, "egl (" + c.platform + ")", options.debugOutput);
        return;
      }
      tried += (tried.empty() ? "" : ", ") + c.platform;
    }
    if (tried.empty()) throw ContextError("egl: no EGL display found (is libegl-mesa0 or the NVIDIA driver installed?)");
    throw ContextError("OpenGL 4.5 core is required, but egl offers " + (offer.empty() ? "no context" : offer) +
                       " (tried " + tried + ")");
  }
  ~EglContext() override {
    if (display_ != EGL_NO_DISPLAY) {
      eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      if (context_ != EGL_NO_CONTEXT) eglDestroyContext(display_, context_);
      eglTerminate(display_);
    }
  }
  GlBackend backend() const override { return GlBackend::Egl; }
  void makeCurrent() override {
    if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
      throw ContextError("egl: eglMakeCurrent failed");
  }

 private:
  bool tryDisplay(const Candidate& c, std::string& offer) {
    EGLint major = 0, minor = 0;
    if (!eglInitialize(c.display, &major, &minor)) return false;
    const char* ext = eglQueryString(c.display, EGL_EXTENSIONS);
    if (!hasExtension(ext, "EGL_KHR_surfaceless_context") || !eglBindAPI(EGL_OPENGL_API)) {
      eglTerminate(c.display);
      return false;
    }
    EGLConfig config = nullptr;
    EGLint n = 0;
    const EGLint withPbuffer[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                                  EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8, EGL_NONE};
    const EGLint anySurface[] = {EGL_SURFACE_TYPE, 0, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    if (!eglChooseConfig(c.display, withPbuffer, &config, 1, &n) || n == 0) {
      if (!eglChooseConfig(c.display, anySurface, &config, 1, &n) || n == 0) {
        eglTerminate(c.display);
        return false;
      }
    }
    const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                              EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    EGLContext context = eglCreateContext(c.display, config, EGL_NO_CONTEXT, attribs);
    if (context == EGL_NO_CONTEXT) {
      if (offer.empty()) {
        if (EGLContext any = eglCreateContext(c.display, config, EGL_NO_CONTEXT, nullptr); any != EGL_NO_CONTEXT) {
          if (eglMakeCurrent(c.display, EGL_NO_SURFACE, EGL_NO_SURFACE, any)) offer = describeFallbackVersion(eglProc);
          eglMakeCurrent(c.display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
          eglDestroyContext(c.display, any);
        }
      }
      eglTerminate(c.display);
      return false;
    }
    display_ = c.display;
    context_ = context;
    return true;
  }

  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
};

}  // namespace

std::unique_ptr<GlContext> createEglContext(const ContextOptions& options) {
  return std::make_unique<EglContext>(options);
}

}  // namespace tallow::gpu::detail
