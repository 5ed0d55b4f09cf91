#pragma once
// Dear ImGui in a GLFW window: the context and the GLFW and OpenGL 3 platform/renderer backends
// (compiled from Debian's libimgui-dev sources, see gpu/CMakeLists.txt), created and destroyed
// together. One per window; the window's GL context must be current.
#include "gpu/key_taps.h"

struct GLFWwindow;

namespace tallow::gpu {

class ImGuiLayer {
 public:
  explicit ImGuiLayer(GLFWwindow* window);
  ~ImGuiLayer();
  ImGuiLayer(const ImGuiLayer&) = delete;
  ImGuiLayer& operator=(const ImGuiLayer&) = delete;

  /// Starts a frame: input of the last events, then the widgets may be built.
  void beginFrame();
  /// Draws the widgets into the current framebuffer (the backend saves and restores GL state).
  void endFrame();

  /// ImGui uses the mouse or keyboard now (the camera must not react to it).
  bool wantsMouse() const;
  bool wantsKeyboard() const;

 private:
  GLFWwindow* window_ = nullptr;
  KeyTaps taps_;
};

}  // namespace tallow::gpu
