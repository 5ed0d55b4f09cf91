#pragma once
// Scripted runs (`tallow view --script FILE`, `tallow capture --script FILE`): a text file of timed
// commands, one per line, each run before the frame it names is rendered:
//
//   # comments start with '#' (at the start of a line or after a space)
//   frame 0  set sss.maps=4            # any registry parameter, value as for --set
//   frame 5  set material="White Grapefruit Juice"
//   frame 10 pause | play | loop on|off | speed 0.5 | seek 3.25
//   frame 12 orbit 30 -10              # degrees: yaw, pitch (camera.position changes)
//   frame 12 pan 0.1 0 | zoom 0.8
//   frame 14 debug map:3               # view only: the debug view (sss/debug_view.h)
//   frame 20 screenshot shot.png       # view only: .png (the window) or .exr (the radiance)
//   frame 20 save-preset saved.json    # view only
//   frame 22 key ctrl+z                # view only: a hotkey, as if pressed (app/playback/hotkeys.h)
//   frame 30 quit                      # view only: close the window after frame 29
//
// Frames count from 0 and must not decrease from line to line. Everything a line can get wrong is
// checked when the file is read, `set` against the registry's types and ranges, so a malformed
// script fails with `FILE:LINE:COL: message` before a frame is drawn; a value the scene refuses
// when it is applied (e.g. light.direction of a point light) fails then, at that line.
#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "app/config/registry.h"
#include "app/playback/hotkeys.h"
#include "sss/debug_view.h"

namespace tallow::app {

enum class ScriptAction { Set, Play, Pause, Loop, Speed, Seek, Orbit, Pan, Zoom, Debug, Screenshot, SavePreset, Key, Quit };

struct ScriptCommand {
  int frame = 0;
  ScriptAction action = ScriptAction::Set;
  std::string where;     ///< "FILE:LINE:COL" of the command word, for errors when it is applied
  std::string key;       ///< Set: the parameter
  nlohmann::json value;  ///< Set: the value, checked against the parameter's type and range
  double a = 0.0, b = 0.0;  ///< Speed, Seek, Zoom: a; Orbit (degrees), Pan (view heights): a, b
  bool on = false;          ///< Loop
  sss::DebugView debug;     ///< Debug
  std::string path;         ///< Screenshot, SavePreset
  Hotkey hotkey = Hotkey::PlayPause;  ///< Key
};

struct Script {
  std::string fileName;
  std::vector<ScriptCommand> commands;  ///< in file order (frames non-decreasing)
  /// The commands of frame `frame`, in file order.
  std::vector<const ScriptCommand*> at(int frame) const;
  int lastFrame() const { return commands.empty() ? -1 : commands.back().frame; }
};

/// Largest frame number a script may name.
inline constexpr int kMaxScriptFrame = 1 << 30;
/// Longest line accepted (a script is typed by hand; longer is a mistake, and bounds the work).
inline constexpr std::size_t kMaxScriptLine = 4096;

/// Reads script text; `fileName` names it in messages. Throws InputError `FILE:LINE:COL: message`.
Script parseScript(std::string_view text, const std::string& fileName, const Registry& registry);
/// Reads a script file (the path as given names it).
Script loadScript(const std::filesystem::path& file, const Registry& registry);

/// The command word of each action, as written in a script.
std::string_view scriptActionName(ScriptAction action);

}  // namespace tallow::app
