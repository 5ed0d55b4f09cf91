#include "app/view/view_hotkeys.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

namespace tallow::app {

std::optional<Hotkey> hotkeyOf(int key, int mods, bool repeat) {
  const bool ctrl = (mods & GLFW_MOD_CONTROL) != 0, shift = (mods & GLFW_MOD_SHIFT) != 0;
  const bool other = (mods & (GLFW_MOD_ALT | GLFW_MOD_SUPER)) != 0;
  if (other) return std::nullopt;
  if (key == GLFW_KEY_LEFT && !ctrl) return Hotkey::StepBack;
  if (key == GLFW_KEY_RIGHT && !ctrl) return Hotkey::StepForward;
  if (repeat) return std::nullopt;  // holding any other key does it once
  if (ctrl) {
    if (key == GLFW_KEY_Z) return shift ? Hotkey::Redo : Hotkey::Undo;
    if (key == GLFW_KEY_Y && !shift) return Hotkey::Redo;
    return std::nullopt;
  }
  if (shift) return std::nullopt;
  switch (key) {
    case GLFW_KEY_SPACE:
      return Hotkey::PlayPause;
    case GLFW_KEY_R:
      return Hotkey::ResetCamera;
    case GLFW_KEY_S:
      return Hotkey::Screenshot;
    case GLFW_KEY_F1:
      return Hotkey::TogglePanel;
    case GLFW_KEY_ESCAPE:
      return Hotkey::Quit;
    default:
      return std::nullopt;
  }
}

HotkeyQueue::HotkeyQueue(GLFWwindow* window) : window_(window) {
  glfwSetWindowUserPointer(window_, this);
  glfwSetKeyCallback(window_, onKey);
}

HotkeyQueue::~HotkeyQueue() {
  glfwSetKeyCallback(window_, nullptr);
  glfwSetWindowUserPointer(window_, nullptr);
}

std::vector<Hotkey> HotkeyQueue::take() {
  std::vector<Hotkey> keys;
  keys.swap(pending_);
  return keys;
}

void HotkeyQueue::onKey(GLFWwindow* window, int key, int, int action, int mods) {
  auto* self = static_cast<HotkeyQueue*>(glfwGetWindowUserPointer(window));
  if (!self || action == GLFW_RELEASE) return;
  // Typing into the panel's file-name field: the keys are text (the flag is the last frame's).
  if (ImGui::GetCurrentContext() && ImGui::GetIO().WantTextInput) return;
  if (const std::optional<Hotkey> hotkey = hotkeyOf(key, mods, action == GLFW_REPEAT)) self->push(*hotkey);
}

}  // namespace tallow::app
