#pragma once
// Everything one run renders: the scene from the preset and the renderer's settings. The
// parameter registry (app/config/registry.h) reads and writes it by key.
#include "sss/render_settings.h"
#include "sss/scene.h"

namespace tallow::app {

struct Config {
  sss::Scene scene;
  sss::RenderSettings render;
};

}  // namespace tallow::app
