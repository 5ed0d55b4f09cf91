#pragma once
// Dear ImGui 1.86 (Debian's libimgui-dev) sees a key only as up or down at the start of each frame:
// a key pressed and released between two frames — a tap during a slow frame, seconds long on
// llvmpipe — was never down for it, so a tapped Enter in a text field was lost (issue 40). KeyTaps
// remembers the presses between two frames and names those that are up again, to be held down for
// one frame (gpu/imgui_layer.cpp); the keys still held are left to the backend.
#include <functional>
#include <vector>

namespace tallow::gpu {

class KeyTaps {
 public:
  /// A press of `key` arrived (GLFW's key callback, action GLFW_PRESS).
  void pressed(int key);
  /// At the start of a frame: the keys pressed since the last call that `down` says are up now, each
  /// once, in the order first pressed. Forgets the presses.
  std::vector<int> tapsToHold(const std::function<bool(int)>& down);

 private:
  std::vector<int> presses_;
};

}  // namespace tallow::gpu
