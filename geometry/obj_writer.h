#pragma once
// Writer for Wavefront OBJ files of a triangle mesh with per-vertex normals (`tallow mesh`'s .obj,
// what DCC tools import as a mesh sequence). Hand-written rather than through a library: the format
// is three kinds of text line (v, vn, f), and the project's dependencies include no OBJ writer.
// Numbers are printed with 9 significant digits, so a float reads back exactly.
#include <filesystem>
#include <string>
#include <vector>

#include "geometry/triangle_mesh.h"

namespace tallow::geometry {

/// The text of the OBJ file of `mesh`: `# comment` lines, then `v x y z` and `vn nx ny nz` per vertex
/// and `f a//a b//b c//c` per triangle (1-based, counter-clockwise from outside). Normals are written
/// unit length; a mesh without one normal per vertex gets computeVertexNormals' normals. Throws std::invalid_argument when a
/// triangle names a vertex that does not exist or a comment holds a line break.
std::string encodeObj(const TriangleMesh& mesh, const std::vector<std::string>& comments = {});

/// encodeObj written atomically (a temporary file, then a rename). Throws std::runtime_error with
/// one line (`cannot write PATH: REASON`) on failure.
void writeObj(const std::filesystem::path& path, const TriangleMesh& mesh, const std::vector<std::string>& comments = {});

}  // namespace tallow::geometry
