#include "app/playback/hotkeys.h"

#include <algorithm>
#include <cctype>
#include <string>

namespace tallow::app {
namespace {

struct Entry {
  Hotkey key;
  std::string_view name;
  std::string_view help;
};
constexpr Entry kEntries[] = {
    {Hotkey::PlayPause, "space", "play or pause"},
    {Hotkey::StepBack, "left", "one frame back (pauses)"},
    {Hotkey::StepForward, "right", "one frame on (pauses)"},
    {Hotkey::ResetCamera, "r", "reset the camera"},
    {Hotkey::Screenshot, "s", "save the window as a numbered PNG"},
    {Hotkey::Undo, "ctrl+z", "undo the last parameter edit"},
    {Hotkey::Redo, "ctrl+y", "redo"},
    {Hotkey::TogglePanel, "f1", "hide or show the panel"},
    {Hotkey::Quit, "escape", "quit"},
};

}  // namespace

std::string_view hotkeyName(Hotkey key) {
  for (const Entry& e : kEntries)
    if (e.key == key) return e.name;
  return "?";
}

std::string_view hotkeyHelp(Hotkey key) {
  for (const Entry& e : kEntries)
    if (e.key == key) return e.help;
  return "";
}

std::vector<std::string_view> hotkeyNames() {
  std::vector<std::string_view> names;
  for (const Entry& e : kEntries) names.push_back(e.name);
  return names;
}

const std::vector<Hotkey>& allHotkeys() {
  static const std::vector<Hotkey> keys = [] {
    std::vector<Hotkey> k;
    for (const Entry& e : kEntries) k.push_back(e.key);
    return k;
  }();
  return keys;
}

std::optional<Hotkey> parseHotkey(std::string_view name) {
  std::string lower(name);
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  if (lower == "esc") return Hotkey::Quit;
  if (lower == "ctrl+shift+z") return Hotkey::Redo;
  for (const Entry& e : kEntries)
    if (e.name == lower) return e.key;
  return std::nullopt;
}

}  // namespace tallow::app
