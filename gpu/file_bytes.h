#pragma once
// Reading the files a user names (images, environment maps, meshes, presets, scripts, tables):
// refused before a byte is read when they are not regular files or larger than their kind's limit,
// and a std::bad_alloc while reading or decoding one becomes a line naming it.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace tallow::gpu {

/// Size limits per kind of file, each far above any real input (the bunny's PLY is 3 MB, a preset
/// 2 kB, a 4K float EXR 130 MB), so that they stop only a wrong or damaged file — a video given as a
/// mesh, a sparse file — before it is read whole, never a scene someone meant.
inline constexpr std::uintmax_t kMaxTextFileBytes = std::uintmax_t{64} << 20;   ///< presets, scripts, materials, shaders
inline constexpr std::uintmax_t kMaxTableFileBytes = std::uintmax_t{1} << 30;   ///< CSV inputs of `probe` and `field`
inline constexpr std::uintmax_t kMaxMeshFileBytes = std::uintmax_t{1} << 30;    ///< PLY meshes: ~40 M triangles
inline constexpr std::uintmax_t kMaxImageFileBytes = std::uintmax_t{2} << 30;   ///< PNG, EXR, HDR

/// Throws std::runtime_error, one line `FILE: …`, when `path` exists but is not a regular file
/// (a character device such as /dev/zero, a FIFO, a socket) or is larger than `maxBytes`, naming
/// `what` ("a PLY mesh") and the limit. A missing file or a folder passes: each reader has its
/// own words for those, said when it opens the file.
void checkInputFile(const std::filesystem::path& path, std::uintmax_t maxBytes, std::string_view what);

/// The whole of a binary file, after checkInputFile. Throws std::runtime_error, one line
/// `FILE: what` (a folder, cannot open, read error, out of memory).
std::vector<std::uint8_t> readFileBytes(const std::filesystem::path& path, std::uintmax_t maxBytes = kMaxImageFileBytes,
                                        std::string_view what = "an image");

/// Throws std::runtime_error `FILE: out of memory reading it (SIZE)`: what a reader says when a
/// std::bad_alloc interrupts reading or decoding `path`.
[[noreturn]] void throwOutOfMemoryReading(const std::filesystem::path& path);

}  // namespace tallow::gpu
