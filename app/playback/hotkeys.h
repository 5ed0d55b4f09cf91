#pragma once
// The view window's hotkeys as actions, apart from GLFW (app/view/view_hotkeys.h maps keys to
// them): scripts name them (`frame 5 key space`), so tests press them through the same path.
#include <optional>
#include <string_view>
#include <vector>

namespace tallow::app {

enum class Hotkey {
  PlayPause,    ///< Space
  StepBack,     ///< ←: one frame back, paused
  StepForward,  ///< →: one frame on, paused
  ResetCamera,  ///< R: the camera the preset started with
  Screenshot,   ///< S: the window as a numbered PNG
  Undo,         ///< Ctrl-Z: the last parameter edit
  Redo,         ///< Ctrl-Y (or Ctrl-Shift-Z)
  TogglePanel,  ///< F1: hide or show the panel
  Quit,         ///< Esc
};

/// The name a script uses: "space", "left", "right", "r", "s", "ctrl+z", "ctrl+y", "f1", "escape".
std::string_view hotkeyName(Hotkey key);
/// Every name, for messages.
std::vector<std::string_view> hotkeyNames();
/// The hotkey of a script's name (case-insensitive; "esc" and "ctrl+shift+z" too); empty if none.
std::optional<Hotkey> parseHotkey(std::string_view name);
/// What the key does, for the panel's help and docs: "play or pause".
std::string_view hotkeyHelp(Hotkey key);
/// Every hotkey, in the order the panel lists them.
const std::vector<Hotkey>& allHotkeys();

}  // namespace tallow::app
