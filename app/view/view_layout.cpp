#include "app/view/view_layout.h"

#include <algorithm>
#include <cmath>

namespace tallow::app {

ViewLayout layoutView(int windowW, int windowH, int panelW, int imageW, int imageH) {
  ViewLayout l;
  const int panel = std::clamp(panelW, 0, std::max(windowW, 0));
  if (panel > 0) l.panel = {0, 0, panel, windowH};
  l.viewport = {panel, 0, std::max(windowW - panel, 0), std::max(windowH, 0)};
  l.image = {l.viewport.x, l.viewport.y, 0, 0};
  if (l.viewport.empty() || imageW <= 0 || imageH <= 0) return l;
  // The largest scale at which the whole image fits, so nothing of it is cut and the aspect holds.
  l.scale = std::min(static_cast<double>(l.viewport.width) / imageW, static_cast<double>(l.viewport.height) / imageH);
  const int w = std::min(static_cast<int>(std::lround(imageW * l.scale)), l.viewport.width);
  const int h = std::min(static_cast<int>(std::lround(imageH * l.scale)), l.viewport.height);
  l.image = {l.viewport.x + (l.viewport.width - w) / 2, l.viewport.y + (l.viewport.height - h) / 2, w, h};
  return l;
}

nlohmann::json layoutJson(const ViewLayout& layout, int windowW, int windowH) {
  const auto box = [](const PixelBox& b) { return nlohmann::json::array({b.x, b.y, b.width, b.height}); };
  return {{"window", {windowW, windowH}},
          {"panel", layout.panel.empty() ? nlohmann::json(nullptr) : box(layout.panel)},
          {"image", box(layout.image)},
          {"scale", layout.scale}};
}

}  // namespace tallow::app
