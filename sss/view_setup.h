#pragma once
// Matrices of the scene camera and of the lights' shadow views, fitted to the scene's bounds.
#include <glm/glm.hpp>

#include <array>

#include "geometry/triangle_mesh.h"
#include "sss/scene.h"

namespace tallow::sss {

struct CameraView {
  glm::mat4 view{1.0f};
  glm::mat4 projection{1.0f};
  glm::mat4 viewProjection{1.0f};
  glm::vec3 position{0.0f};
  glm::vec3 forward{0.0f, 0.0f, -1.0f};
  bool orthographic = false;
};

/// The camera for an image of aspect ratio `aspect` (width / height). Near and far planes enclose
/// `bounds` so that depth precision is spent where the scene is.
CameraView cameraView(const Camera& camera, float aspect, const geometry::Aabb& bounds);

/// Orthographic view along a directional light (`towardLight` unit) whose square covers the
/// bounding sphere of `casters` and whose depth range covers all of `world` (receivers behind the
/// casters must be inside it). `texelWorld` receives the world size of one texel of a `size`² map.
glm::mat4 directionalShadowViewProjection(const glm::vec3& towardLight, const geometry::Aabb& casters,
                                          const geometry::Aabb& world, int size, float& texelWorld);

/// The six cube-face view-projections of a point light (GL face order +X, −X, +Y, −Y, +Z, −Z),
/// 90° frusta from `near` to `range`.
std::array<glm::mat4, 6> cubeFaceViewProjections(const glm::vec3& position, float near, float range);

}  // namespace tallow::sss
