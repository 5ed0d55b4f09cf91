#pragma once
// Writer for PLY files in the layout readPly (geometry/ply_reader.h) reads back exactly:
// binary_little_endian 1.0, vertex x, y, z, nx, ny, nz (float), face list uchar uint vertex_indices.
#include <filesystem>
#include <string>
#include <vector>

#include "geometry/triangle_mesh.h"

namespace tallow::geometry {

/// The bytes of the PLY file of `mesh`. Normals are written unit length, nudged until normalising
/// them again in float changes no bit (so a reader that normalises, as readPly does, reads back the
/// very numbers written); a mesh without one normal per vertex gets computeVertexNormals' normals.
/// Throws std::invalid_argument when a triangle names a vertex that does not exist.
/// `comments` become `comment` lines of the header (one line each; a newline in one is refused).
std::string encodePly(const TriangleMesh& mesh, const std::vector<std::string>& comments = {});

/// encodePly written atomically (gpu::writeFileAtomically: a temporary file, then a rename).
/// Throws std::runtime_error with one line (`cannot write PATH: REASON`) on failure.
void writePly(const std::filesystem::path& path, const TriangleMesh& mesh, const std::vector<std::string>& comments = {});

}  // namespace tallow::geometry
