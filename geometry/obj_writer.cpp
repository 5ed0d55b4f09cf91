#include "geometry/obj_writer.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "gpu/atomic_file.h"

namespace tallow::geometry {

std::string encodeObj(const TriangleMesh& input, const std::vector<std::string>& comments) {
  TriangleMesh withNormals;
  const TriangleMesh* mesh = &input;
  if (input.normals.size() != input.positions.size()) {
    withNormals = input;
    computeVertexNormals(withNormals);
    mesh = &withNormals;
  }
  std::string out;
  for (const std::string& c : comments) {
    if (c.find_first_of("\r\n") != std::string::npos) throw std::invalid_argument("OBJ comment with a line break");
    out += "# " + c + "\n";
  }
  char line[160];
  for (const glm::vec3& p : mesh->positions) {
    std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", p.x, p.y, p.z);
    out += line;
  }
  for (const glm::vec3& stored : mesh->normals) {
    const float length = glm::length(stored);
    const glm::vec3 n = length > 0.0f && std::isfinite(length) ? stored / length : glm::vec3(0.0f, 1.0f, 0.0f);
    std::snprintf(line, sizeof line, "vn %.9g %.9g %.9g\n", n.x, n.y, n.z);
    out += line;
  }
  const std::size_t vertices = mesh->positions.size();
  for (const auto& t : mesh->triangles) {
    for (const std::uint32_t i : t)
      if (i >= vertices) throw std::invalid_argument("triangle names vertex " + std::to_string(i) + " of " +
                                                     std::to_string(vertices));
    std::snprintf(line, sizeof line, "f %u//%u %u//%u %u//%u\n", t[0] + 1, t[0] + 1, t[1] + 1, t[1] + 1, t[2] + 1,
                  t[2] + 1);
    out += line;
  }
  return out;
}

void writeObj(const std::filesystem::path& path, const TriangleMesh& mesh, const std::vector<std::string>& comments) {
  gpu::writeTextFileAtomically(path, encodeObj(mesh, comments));
}

}  // namespace tallow::geometry
