#pragma once
// The shader files embedded into the binary at build time (see cmake/EmbedShaders.cmake).
#include <span>
#include <string_view>

namespace tallow::gpu {

struct EmbeddedFile {
  std::string_view path;      ///< relative to shaders/, forward slashes
  std::string_view contents;  ///< the file, byte for byte
};

/// Every file under shaders/ as it was at build time, sorted by path, then the files from outside
/// shaders/ that shaders include (TALLOW_EXTRA_SHADER_FILES: nanovdb/PNanoVDB.h from libnanovdb-dev).
std::span<const EmbeddedFile> embeddedShaderFiles();

}  // namespace tallow::gpu
