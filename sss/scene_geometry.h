#pragma once
// The scene's shapes on the GPU with their world transforms: meshes read from files (once per
// path) and analytic primitives. Placement rules (documented in docs/presets.md):
//   mesh   — uniformly scaled so that its largest bounding-box extent is `scale` metres, rotated,
//            and placed with its bounding-box bottom centre at `position`;
//   sphere — radius `scale`, centred at `position`;
//   plane  — `size.x × size.z` times `scale`, normal +y (before rotation), centred at `position`;
//   box    — `size` times `scale`, centred at `position`;
//   field  — isosurfaced in the field's own world units (blob centred on the origin, candle base
//            at y = 0, mesh field: bottom centre at the origin), rotated, then moved by `position`.
//            Its triangles come from the renderer's GpuDualContouring (attachField).
#include <glm/glm.hpp>

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "geometry/gpu_dual_contouring.h"
#include "geometry/triangle_mesh.h"
#include "sss/gpu_mesh.h"
#include "sss/scene.h"

namespace tallow::sss {

struct DrawItem {
  int objectIndex = 0;
  const GpuMesh* mesh = nullptr;
  glm::mat4 model{1.0f};
  glm::mat3 normalMatrix{1.0f};
  glm::vec3 albedo{0.8f};
  const geometry::GpuDualContouring* field = nullptr;  ///< field objects: drawn from here instead of `mesh`
  geometry::Aabb worldBounds;  ///< the shape's bounds in world units (empty: a field not attached yet)

  /// Draws the item's triangles with the caller's program bound (attribute 0 position, 1 normal),
  /// `instances` times (gl_InstanceID: layered passes pick their layer by it).
  void draw(int instances = 1) const;
};

class SceneGeometry {
 public:
  /// Loads every mesh file of `scene` (field objects get no shape until attachField) (throws std::runtime_error naming the file when one is
  /// missing or broken) and uploads every shape.
  explicit SceneGeometry(const Scene& scene);
  /// Recomputes transforms and albedos after parameters changed (meshes are not reloaded).
  void update(const Scene& scene);

  const std::vector<DrawItem>& items() const { return items_; }
  geometry::Aabb worldBounds() const { return bounds_; }
  /// Bounds of the shapes that shadow maps are fitted to: every shape but planes (ground planes
  /// are large receivers with nothing beneath them to shadow); all shapes when only planes exist.
  geometry::Aabb casterBounds() const { return casterBounds_.empty() ? bounds_ : casterBounds_; }
  /// Field object `objectIndex` is drawn from `field`; `localBounds` (field units, before the
  /// object's transform) must contain its surface at every time. Call update() afterwards.
  void attachField(int objectIndex, const geometry::GpuDualContouring* field, const geometry::Aabb& localBounds);
  /// Triangles of the meshes and primitives; field triangles are counted by the renderer.
  std::size_t triangleCount() const;
  std::size_t bytes() const;

  /// The object-space mesh of a shape, as it is drawn (for tests and the CPU reference). A mesh file
  /// is read and checked with meshPlacement.
  static geometry::TriangleMesh shapeMesh(const SceneObject& object);

  /// How a mesh file's triangles become an object `scale` metres across: scaled by `factor` about
  /// `anchor` (the centre of its bounding box's bottom), which goes to the origin.
  struct MeshPlacement {
    float factor = 1.0f;
    glm::vec3 anchor{0.0f};
  };
  /// The placement of `mesh` (read from `file`) at `scale`, checked: throws std::runtime_error naming
  /// the file when it cannot be drawn at that scale — its vertices all at one point or on one line
  /// (no area), or an extent that single precision cannot scale to `scale` metres — rather than let
  /// the object vanish or fail later without the file's name.
  static MeshPlacement meshPlacement(const geometry::TriangleMesh& mesh, float scale, const std::filesystem::path& file);
  /// The placement of a mesh whose bounds are `local`, unchecked (computed in double).
  static MeshPlacement placeMesh(const geometry::Aabb& local, float scale);
  /// Object → world transform of `object` whose object-space bounds are `local`.
  static glm::mat4 modelMatrix(const SceneObject& object, const geometry::Aabb& local);

 private:
  struct Shape {
    std::unique_ptr<GpuMesh> gpu;
    geometry::Aabb localBounds;
    const geometry::GpuDualContouring* field = nullptr;
  };
  std::map<std::string, Shape> shapes_;  ///< by mesh path or primitive name
  std::vector<Shape*> objectShapes_;
  std::vector<DrawItem> items_;
  geometry::Aabb bounds_, casterBounds_;
};

}  // namespace tallow::sss
