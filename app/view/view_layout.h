#pragma once
// Where things go in the view window: the panel along the left edge, full height, and the image
// in the rest (its viewport), scaled to fit with its aspect kept and centred (letterboxed), never
// under the panel. Pure arithmetic in framebuffer pixels, origin top left, so tests check it
// without a window.
#include <nlohmann/json.hpp>

namespace tallow::app {

struct PixelBox {
  int x = 0, y = 0, width = 0, height = 0;  ///< top-left origin
  bool empty() const { return width <= 0 || height <= 0; }
  bool overlaps(const PixelBox& o) const {
    return !empty() && !o.empty() && x < o.x + o.width && o.x < x + width && y < o.y + o.height && o.y < y + height;
  }
};

struct ViewLayout {
  PixelBox panel;     ///< empty when hidden
  PixelBox viewport;  ///< the window right of the panel
  PixelBox image;     ///< the picture inside the viewport, aspect kept
  double scale = 1.0; ///< image pixels on screen per rendered pixel
};

/// The layout of a window of `windowW` × `windowH` with a panel `panelW` pixels wide (0: hidden;
/// at most the window) and an image rendered at `imageW` × `imageH`. A viewport too small to hold
/// a pixel gets an empty image.
ViewLayout layoutView(int windowW, int windowH, int panelW, int imageW, int imageH);

/// stats.json's "view" of a frame: {"window": [w, h], "panel": [x, y, w, h] or null, "image": [x, y, w, h]}.
nlohmann::json layoutJson(const ViewLayout& layout, int windowW, int windowH);

}  // namespace tallow::app
