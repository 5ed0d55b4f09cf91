#pragma once
// `tallow view`: the interactive window (GLFW). Without a display it says so and captures the
// preset into out/ instead.
#include <string>

#include "app/setup.h"

namespace tallow::app {

struct ViewOptions {
  SceneOptions scene;
  int frames = 0;  ///< stop after this many frames (0 = until the window closes)
  std::string fallbackOutDir = "out";
};

int runView(const ViewOptions& options);

}  // namespace tallow::app
