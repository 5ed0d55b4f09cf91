#pragma once
// Reader for PLY polygon files (Greg Turk's format, as written by the Stanford scanning repository,
// MeshLab and Blender): ascii 1.0, binary_little_endian 1.0 and binary_big_endian 1.0.
#include <filesystem>
#include <string>
#include <string_view>

#include "geometry/triangle_mesh.h"

namespace tallow::geometry {

/// Reads the `vertex` element (x, y, z required; nx, ny, nz optional) and the `face` element
/// (list `vertex_indices` or `vertex_index`); polygons with more than 3 corners are fan
/// triangulated; other elements and properties are skipped. Stored normals are normalised; if
/// there are none, or any is zero or not finite, all normals are computed from the faces.
/// Throws std::runtime_error with one line: `FILE:LINE: message` for the header and ascii data
/// (1-based line of the file), `FILE: byte OFFSET: message` for binary data.
TriangleMesh readPly(const std::filesystem::path& path);

/// readPly on a file's contents; `nameForErrors` stands for FILE in error messages.
TriangleMesh parsePly(std::string_view data, const std::string& nameForErrors);

}  // namespace tallow::geometry
