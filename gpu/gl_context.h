#pragma once
// One interface for the three ways Tallow gets an OpenGL 4.5 core context: a GLFW window, OSMesa
// (headless on any machine; the default) and EGL (headless on GPU machines, or on Mesa through
// the device or surfaceless platform). After create() the context is current and glad is loaded.
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>

struct GLFWwindow;

namespace tallow::gpu {

enum class GlBackend { Glfw, OsMesa, Egl };

/// "glfw" | "osmesa" | "egl"; throws std::invalid_argument otherwise.
GlBackend parseGlBackend(std::string_view name);
std::string_view glBackendName(GlBackend backend);

struct ContextOptions {
  GlBackend backend = GlBackend::OsMesa;
  int windowWidth = 960;  ///< GLFW only
  int windowHeight = 540;
  std::string title = "Tallow";
  bool visible = true;  ///< GLFW only
  int swapInterval = 1;  ///< GLFW only: glfwSwapInterval (1: vsync, 0: swap at once)
  /// Route GL debug output (KHR_debug) into the log. On by default in debug builds.
#ifdef NDEBUG
  bool debugOutput = false;
#else
  bool debugOutput = true;
#endif
};

/// The context could not be created, or offers less than OpenGL 4.5 core. what() is one line.
class ContextError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct GlInfo {
  std::string vendor, renderer, version, glsl;
  int major = 0, minor = 0;
};

class GlContext {
 public:
  virtual ~GlContext() = default;
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  /// Creates, makes current and loads GL. Throws ContextError.
  static std::unique_ptr<GlContext> create(const ContextOptions& options);

  virtual GlBackend backend() const = 0;
  virtual void makeCurrent() = 0;
  /// A second context sharing this one's objects (textures, buffers, programs, sync objects; not
  /// framebuffers or vertex arrays), for a render thread: created and destroyed on this thread,
  /// made current on the other. GLFW only (an invisible window); throws ContextError elsewhere.
  virtual std::unique_ptr<GlContext> createShared() const;
  /// The window of a GLFW context, nullptr for headless ones.
  virtual GLFWwindow* window() const { return nullptr; }
  const GlInfo& info() const { return info_; }

 protected:
  GlContext() = default;
  /// Loads glad through `getProcAddress`, checks for 4.5 and fills info_. Throws ContextError.
  void loadGl(void* (*getProcAddress)(const char*), std::string_view backendName, bool debugOutput);
  void setInfo(const GlInfo& info) { info_ = info; }

 private:
  GlInfo info_;
};

/// True when a window can be opened: an X11 or Wayland display is named and GLFW can reach it.
/// Leaves GLFW initialised when it returns true (the GLFW context's destructor terminates it).
bool displayAvailable();

}  // namespace tallow::gpu
