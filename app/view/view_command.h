#pragma once
// `tallow view`: the interactive window (GLFW + Dear ImGui, docs/view.md): a panel generated from
// the parameter registry, per-pass timings, preset playback, mouse camera, debug views, screenshots
// and presets saved from the window, scripted runs. Without a display it says so and captures the
// preset into out/ instead.
#include <optional>
#include <string>
#include <vector>

#include "app/config/setup.h"
#include "app/playback/playback.h"

namespace tallow::app {

struct ViewOptions {
  SceneOptions scene;
  int frames = 0;  ///< stop after this many frames (0 = until the window closes)
  std::string fallbackOutDir = "out";
  /// Saved after the last frame: .png the window as shown (panel included), .exr the radiance.
  std::vector<std::string> screenshots;
  std::string savePreset;  ///< saved after the last frame: a preset that reproduces the window
  std::string script;      ///< timed commands (app/playback/view_script.h)
  std::string stats;       ///< stats.json of the run, written when the window closes
  std::string reference;   ///< EXR for the difference debug view
  std::string debugView;   ///< initial debug view (sss/debug_view.h), e.g. "map:3"
  double fps = 0.0;        ///< > 0: the clock advances 1/fps per frame instead of by wall time
  /// By wall time, the clock advances at most this much per frame (app/playback/playback.h's
  /// cappedStep); 0: no cap.
  double maxStepS = kDefaultMaxStepS;
  std::optional<double> timeS;  ///< animation time of the first frame (default: the preset's start_s)
  bool paused = false;     ///< start with the animation paused
  bool hidePanel = false;  ///< no ImGui panel (screenshots of the image alone)
  bool vsync = true;       ///< swap at the display's refresh (false: no wait in glfwSwapBuffers)
};

int runView(const ViewOptions& options);

}  // namespace tallow::app
