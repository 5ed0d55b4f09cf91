#pragma once
// The view window's keyboard: GLFW key events mapped to hotkeys (app/playback/hotkeys.h) and queued
// by GLFW's key callback as they arrive, so that a key pressed and released between two frames — a
// tap at one frame per second — is still seen, as polling the key's state once a frame would not.
// Scripts push their `key` commands into the same queue.
#include <optional>
#include <vector>

#include "app/playback/hotkeys.h"

struct GLFWwindow;

namespace tallow::app {

/// The hotkey of a GLFW key event with modifiers `mods` (GLFW_MOD_*), `repeat` when the key is held
/// (only the frame steps repeat); empty for any other key or combination.
std::optional<Hotkey> hotkeyOf(int key, int mods, bool repeat);

class HotkeyQueue {
 public:
  /// Installs the key callback. Create it before gpu::ImGuiLayer, whose GLFW backend then passes
  /// every key on to it; keys typed into a text field of the panel are not hotkeys.
  explicit HotkeyQueue(GLFWwindow* window);
  ~HotkeyQueue();
  HotkeyQueue(const HotkeyQueue&) = delete;
  HotkeyQueue& operator=(const HotkeyQueue&) = delete;

  void push(Hotkey key) { pending_.push_back(key); }
  /// The hotkeys since the last call, in the order they came.
  std::vector<Hotkey> take();

 private:
  static void onKey(GLFWwindow* window, int key, int scancode, int action, int mods);

  GLFWwindow* window_;
  std::vector<Hotkey> pending_;
};

}  // namespace tallow::app
