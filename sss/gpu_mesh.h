#pragma once
// A triangle mesh in GPU buffers: interleaved position + normal, 32-bit indices.
#include "geometry/triangle_mesh.h"
#include "gpu/gl_objects.h"

namespace tallow::sss {

class GpuMesh {
 public:
  explicit GpuMesh(const geometry::TriangleMesh& mesh);
  /// Binds its vertex array and draws every triangle, `instances` times (gl_InstanceID).
  void draw(int instances = 1) const;
  std::size_t triangleCount() const { return triangles_; }
  std::size_t bytes() const { return vertices_.size() + indices_.size(); }

 private:
  gpu::Buffer vertices_, indices_;
  gpu::VertexArray vao_;
  std::size_t triangles_ = 0;
};

}  // namespace tallow::sss
