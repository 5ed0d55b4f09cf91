#pragma once
// Sizes in messages: "1.5 GiB", "12.0 MiB", "512 bytes". Header-only, so that the GL-free readers
// (and the fuzz targets built from them) can name sizes too.
#include <cstddef>
#include <cstdio>
#include <string>

namespace tallow::gpu {

inline std::string formatBytes(std::size_t bytes) {
  constexpr std::size_t kMiB = std::size_t{1} << 20, kGiB = std::size_t{1} << 30;
  char text[32];
  const double b = static_cast<double>(bytes);
  if (bytes >= kGiB) std::snprintf(text, sizeof text, "%.1f GiB", b / static_cast<double>(kGiB));
  else if (bytes >= kMiB) std::snprintf(text, sizeof text, "%.1f MiB", b / static_cast<double>(kMiB));
  else std::snprintf(text, sizeof text, "%zu bytes", bytes);
  return text;
}

}  // namespace tallow::gpu
