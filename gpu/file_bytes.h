#pragma once
// The whole of a binary file the user named (an image, an environment map), for the readers that
// decode from memory.
#include <cstdint>
#include <filesystem>
#include <vector>

namespace tallow::gpu {

/// Throws std::runtime_error, one line `FILE: what` (a folder, cannot open, read error).
std::vector<std::uint8_t> readFileBytes(const std::filesystem::path& path);

}  // namespace tallow::gpu
