#include "sss/view_setup.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace tallow::sss {
namespace {
glm::vec3 safeUp(const glm::vec3& forward, const glm::vec3& up) {
  return std::abs(glm::dot(glm::normalize(up), forward)) > 0.999f
             ? (std::abs(forward.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0))
             : up;
}
}  // namespace

CameraView cameraView(const Camera& camera, float aspect, const geometry::Aabb& bounds) {
  CameraView v;
  v.position = camera.position;
  v.forward = glm::normalize(camera.target - camera.position);
  v.orthographic = camera.orthographic;
  v.view = glm::lookAt(camera.position, camera.target, safeUp(v.forward, camera.up));
  const glm::vec3 centre = bounds.empty() ? camera.target : bounds.centre();
  const float radius = bounds.empty() ? 1.0f : std::max(0.5f * glm::length(bounds.size()), 1e-6f);
  const float distance = glm::dot(centre - camera.position, v.forward);
  float far = distance + 1.01f * radius;
  if (camera.orthographic) {
    const float h = 0.5f * camera.orthoHeight;
    v.projection = glm::ortho(-h * aspect, h * aspect, -h, h, distance - 1.01f * radius, far);
  } else {
    far = std::max(far, 1e-3f);
    const float near = std::max(distance - 1.01f * radius, far * 1e-4f);
    v.projection = glm::perspective(glm::radians(camera.fovYDeg), aspect, near, far);
  }
  v.viewProjection = v.projection * v.view;
  return v;
}

glm::mat4 directionalShadowViewProjection(const glm::vec3& towardLight, const geometry::Aabb& casters,
                                          const geometry::Aabb& world, int size, float& texelWorld) {
  const glm::vec3 centre = casters.centre();
  const float radius = std::max(0.5f * glm::length(casters.size()), 1e-6f) * 1.01f;
  // The eye stands beyond all geometry toward the light; the far plane lies beyond all of it too.
  const float reach = glm::length(world.centre() - centre) + 0.5f * glm::length(world.size()) * 1.01f;
  const float depth = std::max(reach, radius);
  const glm::vec3 forward = -glm::normalize(towardLight);
  const glm::mat4 view = glm::lookAt(centre - forward * depth, centre, safeUp(forward, glm::vec3(0, 1, 0)));
  const glm::mat4 projection = glm::ortho(-radius, radius, -radius, radius, 0.0f, 2.0f * depth);
  texelWorld = 2.0f * radius / static_cast<float>(size);
  return projection * view;
}

std::array<glm::mat4, 6> cubeFaceViewProjections(const glm::vec3& p, float near, float range) {
  const glm::mat4 projection = glm::perspective(glm::radians(90.0f), 1.0f, near, range);
  // Cube-map face orientation conventions of the GL specification (Table 8.19).
  const glm::vec3 dirs[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  const glm::vec3 ups[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
  std::array<glm::mat4, 6> out;
  for (int f = 0; f < 6; ++f) out[static_cast<std::size_t>(f)] = projection * glm::lookAt(p, p + dirs[f], ups[f]);
  return out;
}

}  // namespace tallow::sss
