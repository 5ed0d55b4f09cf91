// GLFW: the interactive window.
#include <glad/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <cstdlib>
#include <string>

#include "gpu/gl_context_backends.h"

namespace tallow::gpu {
namespace {

std::string& lastGlfwError() {
  static std::string error;
  return error;
}

void glfwErrorCallback(int, const char* description) { lastGlfwError() = description ? description : "?"; }

bool initGlfw() {
  glfwSetErrorCallback(glfwErrorCallback);
  return glfwInit() == GLFW_TRUE;
}

void* glfwProc(const char* name) { return reinterpret_cast<void*>(glfwGetProcAddress(name)); }

class GlfwContext final : public GlContext {
 public:
  /// An invisible window whose context shares `share`'s objects (createShared).
  GlfwContext(GLFWwindow* share, const GlInfo& info) : shared_(true) {
    glfwDefaultWindowHints();
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_VISIBLE, GLFW_FALSE);
    window_ = glfwCreateWindow(16, 16, "Tallow render thread", nullptr, share);
    if (!window_) throw ContextError("glfw: cannot create a shared context for the render thread: " + lastGlfwError());
    setInfo(info);  // the same driver: glad's entry points serve both contexts
  }
  explicit GlfwContext(const ContextOptions& options) {
    if (!initGlfw()) throw ContextError("glfw: cannot open a window: " + lastGlfwError());
    glfwDefaultWindowHints();
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, options.debugOutput ? GLFW_TRUE : GLFW_FALSE);
    glfwWindowHint(GLFW_VISIBLE, options.visible ? GLFW_TRUE : GLFW_FALSE);
    window_ = glfwCreateWindow(options.windowWidth, options.windowHeight, options.title.c_str(), nullptr, nullptr);
    if (!window_) {
      const std::string reason = lastGlfwError();
      // What does the display offer? Any context will do for reading GL_VERSION.
      std::string offer = "no context (" + reason + ")";
      glfwDefaultWindowHints();
      glfwWindowHint(GLFW_VISIBLE, GLFW_FALSE);
      if (GLFWwindow* any = glfwCreateWindow(16, 16, "probe", nullptr, nullptr)) {
        glfwMakeContextCurrent(any);
        offer = detail::describeFallbackVersion(glfwProc);
        glfwDestroyWindow(any);
      }
      glfwTerminate();
      throw ContextError("OpenGL 4.5 core is required, but glfw offers " + offer);
    }
    makeCurrent();
    glfwSwapInterval(options.swapInterval);
    loadGl(glfwProc, "glfw", options.debugOutput);
  }
  ~GlfwContext() override {
    if (window_) glfwDestroyWindow(window_);
    if (!shared_) glfwTerminate();
  }
  GlBackend backend() const override { return GlBackend::Glfw; }
  std::unique_ptr<GlContext> createShared() const override {
    return std::make_unique<GlfwContext>(window_, info());
  }
  void makeCurrent() override { glfwMakeContextCurrent(window_); }
  GLFWwindow* window() const override { return window_; }

 private:
  GLFWwindow* window_ = nullptr;
  bool shared_ = false;  ///< made by createShared: GLFW stays initialised for the window it shares
};

}  // namespace

bool displayAvailable() {
  const char* x11 = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  if ((!x11 || !*x11) && (!wayland || !*wayland)) return false;
  // GLFW stays initialised (the window's context reuses it; glfwInit is then a no-op): closing the
  // display connection here would make a server that resets when its last client leaves (Xvfb's
  // default) refuse the window's connection, made a moment later, while it resets.
  return initGlfw();
}

namespace detail {
std::unique_ptr<GlContext> createGlfwContext(const ContextOptions& options) {
  return std::make_unique<GlfwContext>(options);
}
}  // namespace detail

}  // namespace tallow::gpu
