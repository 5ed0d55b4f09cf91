#include "geometry/ply_writer.h"

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>

#include "gpu/atomic_file.h"

namespace tallow::geometry {
namespace {

static_assert(std::endian::native == std::endian::little, "encodePly stores the host's floats as little-endian");

/// Normalising a float vector twice can move the last bit; a few rounds reach a vector that
/// normalisation keeps (in practice one or two). Not-finite or zero normals become (0, 1, 0), as in
/// computeVertexNormals.
glm::vec3 stableUnit(glm::vec3 n) {
  constexpr int kMaxRounds = 4;
  for (int i = 0; i < kMaxRounds; ++i) {
    const float length = glm::length(n);
    if (!(length > 0.0f) || !std::isfinite(length)) return {0.0f, 1.0f, 0.0f};
    const glm::vec3 m = n / length;
    if (m == n) break;
    n = m;
  }
  return n;
}

template <class T>
void append(std::string& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out.append(bytes, sizeof(T));
}

}  // namespace

std::string encodePly(const TriangleMesh& input, const std::vector<std::string>& comments) {
  const TriangleMesh* mesh = &input;
  TriangleMesh withNormals;
  if (input.normals.size() != input.positions.size()) {
    withNormals = input;
    computeVertexNormals(withNormals);
    mesh = &withNormals;
  }
  const std::size_t vertexCount = mesh->positions.size();
  for (const auto& t : mesh->triangles)
    for (const std::uint32_t v : t)
      if (v >= vertexCount) throw std::invalid_argument("encodePly: a triangle names vertex " + std::to_string(v) +
                                                        " of " + std::to_string(vertexCount));
  std::string out = "ply\nformat binary_little_endian 1.0\ncomment written by tallow\n";
  for (const std::string& c : comments) {
    if (c.find_first_of("\r\n") != std::string::npos) throw std::invalid_argument("encodePly: a comment of two lines");
    out += "comment " + c + "\n";
  }
  out += "element vertex " + std::to_string(vertexCount) + "\n";
  for (const char* p : {"x", "y", "z", "nx", "ny", "nz"}) out += std::string("property float ") + p + "\n";
  out += "element face " + std::to_string(mesh->triangles.size()) + "\n";
  out += "property list uchar uint vertex_indices\nend_header\n";
  constexpr std::size_t kVertexBytes = 6 * sizeof(float);
  constexpr std::size_t kFaceBytes = 1 + 3 * sizeof(std::uint32_t);
  out.reserve(out.size() + vertexCount * kVertexBytes + mesh->triangles.size() * kFaceBytes);
  for (std::size_t v = 0; v < vertexCount; ++v) {
    const glm::vec3 p = mesh->positions[v];
    const glm::vec3 n = stableUnit(mesh->normals[v]);
    for (int k = 0; k < 3; ++k) append(out, p[k]);
    for (int k = 0; k < 3; ++k) append(out, n[k]);
  }
  for (const auto& t : mesh->triangles) {
    append(out, std::uint8_t{3});
    for (const std::uint32_t v : t) append(out, v);
  }
  return out;
}

void writePly(const std::filesystem::path& path, const TriangleMesh& mesh, const std::vector<std::string>& comments) {
  gpu::writeTextFileAtomically(path, encodePly(mesh, comments));
}

}  // namespace tallow::geometry
