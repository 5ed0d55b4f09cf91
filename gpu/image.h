#pragma once
// A linear RGBA float image in memory, row 0 at the top (as written to PNG/EXR).
#include <glm/glm.hpp>

#include <cstddef>
#include <vector>

namespace tallow::gpu {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<glm::vec4> pixels;  ///< width × height, row-major, top row first

  Image() = default;
  Image(int w, int h) : width(w), height(h), pixels(static_cast<std::size_t>(w) * h, glm::vec4(0)) {}
  glm::vec4& at(int x, int y) { return pixels[static_cast<std::size_t>(y) * width + x]; }
  const glm::vec4& at(int x, int y) const { return pixels[static_cast<std::size_t>(y) * width + x]; }
};

}  // namespace tallow::gpu
