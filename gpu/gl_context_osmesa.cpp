// OSMesa: Mesa's off-screen context (llvmpipe). Tallow always renders into its own framebuffer
// objects, so the OSMesa buffer is a 1×1 dummy that only satisfies MakeCurrent.
//
// libOSMesa is loaded with dlopen when an OSMesa context is first asked for, not linked: it pulls
// in Mesa's LLVM (about 200 MB of libraries with its own dependencies), which a GPU machine never
// needs, so the device bundle (scripts/device_bundle.sh) can leave it out and still start.
#include <glad/gl.h>
// glad defines __gl_h_, so osmesa.h's own #include <GL/gl.h> is skipped. Only its types and
// declarations are used; every function is called through a pointer from dlsym.
#include <GL/osmesa.h>
#include <dlfcn.h>

#include <array>
#include <string>

#include "gpu/gl_context_backends.h"

namespace tallow::gpu::detail {
namespace {

/// The OSMesa entry points Tallow calls, resolved once from the first library that loads.
struct OsMesaApi {
  decltype(&OSMesaCreateContextAttribs) createContextAttribs = nullptr;
  decltype(&OSMesaCreateContextExt) createContextExt = nullptr;
  decltype(&OSMesaMakeCurrent) makeCurrent = nullptr;
  decltype(&OSMesaDestroyContext) destroyContext = nullptr;
  decltype(&OSMesaGetProcAddress) getProcAddress = nullptr;
  std::string error;  ///< why loading failed; empty when every pointer is set
};

template <class F>
bool resolve(void* library, const char* name, F& out, std::string& error) {
  out = reinterpret_cast<F>(dlsym(library, name));
  if (!out) error = std::string("osmesa: ") + name + " missing from libOSMesa";
  return out != nullptr;
}

OsMesaApi loadOsMesa() {
  OsMesaApi api;
  // Debian 12's soname first; .so.6 is the older classic OSMesa's. Never unloaded: Mesa keeps
  // allocations and thread-local state for the life of the process.
  void* library = nullptr;
  std::string tried;
  for (const char* name : {"libOSMesa.so.8", "libOSMesa.so.6", "libOSMesa.so"}) {
    if ((library = dlopen(name, RTLD_NOW | RTLD_LOCAL)) != nullptr) break;
    tried = dlerror();
  }
  if (!library) {
    api.error = "osmesa: cannot load libOSMesa (" + tried + "); install libosmesa6 or use --gl egl";
    return api;
  }
  if (resolve(library, "OSMesaCreateContextAttribs", api.createContextAttribs, api.error) &&
      resolve(library, "OSMesaCreateContextExt", api.createContextExt, api.error) &&
      resolve(library, "OSMesaMakeCurrent", api.makeCurrent, api.error) &&
      resolve(library, "OSMesaDestroyContext", api.destroyContext, api.error) &&
      resolve(library, "OSMesaGetProcAddress", api.getProcAddress, api.error))
    api.error.clear();
  return api;
}

/// Loaded on first use (thread-safe static initialisation); a failure is remembered and reported
/// by every later attempt with the same line.
const OsMesaApi& osmesa() {
  static const OsMesaApi api = loadOsMesa();
  if (!api.error.empty()) throw ContextError(api.error);
  return api;
}

void* osmesaProc(const char* name) { return reinterpret_cast<void*>(osmesa().getProcAddress(name)); }

class OsMesaContext final : public GlContext {
 public:
  explicit OsMesaContext(const ContextOptions& options) : api_(osmesa()) {
    const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24,
                           OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION, 4, OSMESA_CONTEXT_MINOR_VERSION, 5, 0};
    context_ = api_.createContextAttribs(attribs, nullptr);
    if (!context_) {
      // Say what is on offer instead: any context will do for reading GL_VERSION.
      std::string offer = "no context at all";
      if (OSMesaContext any = api_.createContextExt(OSMESA_RGBA, 24, 0, 0, nullptr)) {
        if (api_.makeCurrent(any, buffer_.data(), GL_UNSIGNED_BYTE, 1, 1)) offer = describeFallbackVersion(osmesaProc);
        api_.destroyContext(any);
      }
      throw ContextError("OpenGL 4.5 core is required, but osmesa offers " + offer);
    }
    makeCurrent();
    loadGl(osmesaProc, "osmesa", options.debugOutput);
  }
  ~OsMesaContext() override {
    if (context_) api_.destroyContext(context_);
  }
  GlBackend backend() const override { return GlBackend::OsMesa; }
  void makeCurrent() override {
    if (!api_.makeCurrent(context_, buffer_.data(), GL_UNSIGNED_BYTE, 1, 1))
      throw ContextError("osmesa: OSMesaMakeCurrent failed");
  }

 private:
  const OsMesaApi& api_;
  OSMesaContext context_ = nullptr;
  std::array<unsigned char, 4> buffer_{};
};

}  // namespace

std::unique_ptr<GlContext> createOsMesaContext(const ContextOptions& options) {
  return std::make_unique<OsMesaContext>(options);
}

}  // namespace tallow::gpu::detail
