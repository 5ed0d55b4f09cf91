#pragma once
// What the user's controls do to a running scene, for both the view window (panel, mouse, script)
// and capture (script): every change of the configuration goes through the registry's setters, as
// --set and presets do, so a value the registry refuses is refused here too.
#include "app/config/config.h"
#include "app/config/registry.h"
#include "app/playback/playback.h"
#include "app/playback/view_script.h"

namespace tallow::app {

/// Sets camera.position, camera.target and (orthographic) camera.height from `camera` through the
/// registry. Throws InputError with the registry's message.
void setCamera(Config& config, const Registry& registry, const sss::Camera& camera);

/// Applies a command that acts on the configuration, the clock or the camera (set, play, pause,
/// loop, speed, seek, orbit, pan, zoom) and returns true; returns false, doing nothing, for the
/// window's own commands (debug, screenshot, save-preset, key, quit). Throws InputError
/// "FILE:LINE:COL: <key>: <message>" when the scene refuses a value.
bool applyScriptCommand(const ScriptCommand& command, Config& config, const Registry& registry, Playback& playback);

/// The commands only the window runs (true for debug, screenshot, save-preset, key, quit).
bool windowOnly(ScriptAction action);

}  // namespace tallow::app
