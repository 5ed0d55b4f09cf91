#include "sss/gpu_mesh.h"

#include <stdexcept>
#include <vector>

namespace tallow::sss {

GpuMesh::GpuMesh(const geometry::TriangleMesh& mesh) : triangles_(mesh.triangles.size()) {
  if (mesh.normals.size() != mesh.positions.size())
    throw std::logic_error("GpuMesh: the mesh needs one normal per vertex");
  std::vector<float> interleaved;
  interleaved.reserve(mesh.positions.size() * 6);
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const glm::vec3& p = mesh.positions[i];
    const glm::vec3& n = mesh.normals[i];
    interleaved.insert(interleaved.end(), {p.x, p.y, p.z, n.x, n.y, n.z});
  }
  vertices_ = gpu::Buffer(interleaved.size() * sizeof(float), interleaved.data(), 0);
  indices_ = gpu::Buffer(mesh.triangles.size() * sizeof(mesh.triangles[0]), mesh.triangles.data(), 0);
  vao_.setAttribute(0, vertices_, 0, 6 * sizeof(float), 3);
  vao_.setAttribute(1, vertices_, 3 * sizeof(float), 6 * sizeof(float), 3);
  vao_.setIndexBuffer(indices_);
}

void GpuMesh::draw(int instances) const {
  vao_.bind();
  glDrawElementsInstanced(GL_TRIANGLES, static_cast<GLsizei>(triangles_ * 3), GL_UNSIGNED_INT, nullptr, instances);
}

}  // namespace tallow::sss
