// OSMesa: Mesa's off-screen context (llvmpipe). Tallow always renders into its own framebuffer
// objects, so the OSMesa buffer is a 1×1 dummy that only satisfies MakeCurrent.
#include <glad/gl.h>
// glad defines __gl_h_, so osmesa.h's own #include <GL/gl.h> is skipped.
#include <GL/osmesa.h>

#include <array>

#include "gpu/gl_context_backends.h"

namespace tallow::gpu::detail {
namespace {

void* osmesaProc(const char* name) { return reinterpret_cast<void*>(OSMesaGetProcAddress(name)); }

class OsMesaContext final : public GlContext {
 public:
  explicit OsMesaContext(const ContextOptions& options) {
    const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24,
                           OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION, 4, OSMESA_CONTEXT_MINOR_VERSION, 5, 0};
    context_ = OSMesaCreateContextAttribs(attribs, nullptr);
    if (!context_) {
      // Say what is on offer instead: any context will do for reading GL_VERSION.
      std::string offer = "no context at all";
      if (OSMesaContext any = OSMesaCreateContextExt(OSMESA_RGBA, 24, 0, 0, nullptr)) {
        if (OSMesaMakeCurrent(any, buffer_.data(), GL_UNSIGNED_BYTE, 1, 1)) offer = describeFallbackVersion(osmesaProc);
        OSMesaDestroyContext(any);
      }
      throw ContextError("OpenGL 4.5 core is required, but osmesa offers " + offer);
    }
    makeCurrent();
    loadGl(osmesaProc, "osmesa", options.debugOutput);
  }
  ~OsMesaContext() override {
    if (context_) OSMesaDestroyContext(context_);
  }
  GlBackend backend() const override { return GlBackend::OsMesa; }
  void makeCurrent() override {
    if (!OSMesaMakeCurrent(context_, buffer_.data(), GL_UNSIGNED_BYTE, 1, 1))
      throw ContextError("osmesa: OSMesaMakeCurrent failed");
  }

 private:
  OSMesaContext context_ = nullptr;
  std::array<unsigned char, 4> buffer_{};
};

}  // namespace

std::unique_ptr<GlContext> createOsMesaContext(const ContextOptions& options) {
  return std::make_unique<OsMesaContext>(options);
}

}  // namespace tallow::gpu::detail
