#include "sss/scene_geometry.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "geometry/ply_reader.h"
#include "geometry/primitives.h"

namespace tallow::sss {
namespace {

constexpr int kSphereRings = 96;     // fine enough that shading error stays below 1/255
constexpr int kSphereSegments = 192;
constexpr int kHollowCylinderSegments = 128;  // chord sag 0.03% of the radius

std::string shapeKey(const SceneObject& o) {
  switch (o.shape) {
    case ShapeKind::Mesh: return "mesh:" + o.meshPath.string();
    case ShapeKind::Sphere: return "sphere";
    case ShapeKind::Plane: return "plane";
    case ShapeKind::Box: return "box";
    case ShapeKind::HollowCylinder: {  // the mesh is built in metres from the size: one per size
      char key[96];
      std::snprintf(key, sizeof key, "hollow-cylinder:%.9g,%.9g,%.9g", o.size.x, o.size.y, o.size.z);
      return key;
    }
    case ShapeKind::Field: break;  // one shape per object, keyed by index in the constructor
  }
  return "?";
}

}  // namespace

geometry::TriangleMesh SceneGeometry::shapeMesh(const SceneObject& object) {
  switch (object.shape) {
    case ShapeKind::Mesh: {
      geometry::TriangleMesh mesh = geometry::readPly(object.meshPath);
      meshPlacement(mesh, object.transform.scale, object.meshPath);  // throws, naming the file
      return mesh;
    }
    case ShapeKind::Sphere: return geometry::makeSphere(kSphereRings, kSphereSegments);
    case ShapeKind::Plane: return geometry::makePlane();
    case ShapeKind::Box: return geometry::makeBox();
    case ShapeKind::HollowCylinder:
      // size = (inner radius, outer radius, height); the bottom is as thick as the wall.
      return geometry::makeHollowCylinder(object.size.x, object.size.y, object.size.z, object.size.y - object.size.x,
                                          kHollowCylinderSegments);
    case ShapeKind::Field: break;
  }
  throw std::logic_error("unknown shape");
}

SceneGeometry::MeshPlacement SceneGeometry::placeMesh(const geometry::Aabb& local, float scale) {
  // In double: the float difference of ±3e38 overflows.
  const glm::dvec3 size = glm::dvec3(local.max) - glm::dvec3(local.min);
  const double extent = std::max(size.x, std::max(size.y, size.z));
  MeshPlacement p;
  p.factor = extent > 0.0 ? static_cast<float>(static_cast<double>(scale) / extent) : 1.0f;
  p.anchor = glm::vec3(0.5 * (glm::dvec3(local.min) + glm::dvec3(local.max)));
  p.anchor.y = local.min.y;
  return p;
}

SceneGeometry::MeshPlacement SceneGeometry::meshPlacement(const geometry::TriangleMesh& mesh, float scale,
                                                         const std::filesystem::path& file) {
  const geometry::Aabb b = mesh.bounds();
  const auto fail = [&](const std::string& why) { throw std::runtime_error(file.string() + ": " + why); };
  const auto number = [](double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return std::string(text);
  };
  if (b.empty() || b.min == b.max) fail("its vertices are all at one point: there is nothing to draw at any scale");
  const MeshPlacement p = placeMesh(b, scale);
  const glm::dvec3 size = glm::dvec3(b.max) - glm::dvec3(b.min);
  // A factor below float's normal range (or 0, or infinite) would flatten or blow up the object.
  if (!(p.factor >= std::numeric_limits<float>::min()) || !std::isfinite(p.factor) || !std::isfinite(p.anchor.x) ||
      !std::isfinite(p.anchor.z))
    fail("its extent of " + number(std::max(size.x, std::max(size.y, size.z))) + " cannot be scaled to " +
         number(scale) + " m in single precision; rescale the file's coordinates");
  // The area the triangles will have once placed: none means the object would vanish.
  double area = 0.0;
  for (const auto& t : mesh.triangles) {
    const auto at = [&](int k) { return (glm::dvec3(mesh.positions[t[k]]) - glm::dvec3(p.anchor)) * double(p.factor); };
    area += 0.5 * glm::length(glm::cross(at(1) - at(0), at(2) - at(0)));
  }
  if (!(area > 0.0))
    fail("its triangles have no area (every vertex on one line): there is nothing to draw at any scale");
  return p;
}

glm::mat4 SceneGeometry::modelMatrix(const SceneObject& o, const geometry::Aabb& local) {
  const Transform& t = o.transform;
  glm::mat4 rotation(1.0f);
  rotation = glm::rotate(rotation, glm::radians(t.rotationDeg.z), glm::vec3(0, 0, 1));
  rotation = glm::rotate(rotation, glm::radians(t.rotationDeg.y), glm::vec3(0, 1, 0));
  rotation = glm::rotate(rotation, glm::radians(t.rotationDeg.x), glm::vec3(1, 0, 0));
  glm::mat4 shape(1.0f);
  switch (o.shape) {
    case ShapeKind::Mesh: {
      const MeshPlacement p = placeMesh(local, t.scale);  // checked by meshPlacement when the mesh was read
      shape = glm::scale(glm::mat4(1.0f), glm::vec3(p.factor)) * glm::translate(glm::mat4(1.0f), -p.anchor);
      break;
    }
    case ShapeKind::Sphere: shape = glm::scale(glm::mat4(1.0f), glm::vec3(t.scale)); break;
    case ShapeKind::Plane: shape = glm::scale(glm::mat4(1.0f), glm::vec3(o.size.x, 1.0f, o.size.z) * t.scale); break;
    case ShapeKind::Box: shape = glm::scale(glm::mat4(1.0f), o.size * t.scale); break;
    case ShapeKind::HollowCylinder: shape = glm::scale(glm::mat4(1.0f), glm::vec3(t.scale)); break;  // anchor: bottom centre
    case ShapeKind::Field: break;  // already in world units (see the header)
  }
  return glm::translate(glm::mat4(1.0f), t.position) * rotation * shape;
}

SceneGeometry::SceneGeometry(const Scene& scene) {
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const SceneObject& o = scene.objects[i];
    if (o.shape == ShapeKind::Field) {
      objectShapes_.push_back(&shapes_.emplace("field:" + std::to_string(i), Shape{}).first->second);
      continue;
    }
    const std::string key = shapeKey(o);
    auto it = shapes_.find(key);
    if (it == shapes_.end()) {
      geometry::TriangleMesh mesh = shapeMesh(o);
      if (mesh.normals.size() != mesh.positions.size()) geometry::computeVertexNormals(mesh);
      Shape shape;
      shape.localBounds = mesh.bounds();
      shape.gpu = std::make_unique<GpuMesh>(mesh);
      it = shapes_.emplace(key, std::move(shape)).first;
    }
    objectShapes_.push_back(&it->second);
  }
  update(scene);
}

void SceneGeometry::update(const Scene& scene) {
  if (scene.objects.size() != objectShapes_.size())
    throw std::logic_error("SceneGeometry::update: the scene's objects changed; rebuild instead");
  items_.clear();
  bounds_ = geometry::Aabb{};
  casterBounds_ = geometry::Aabb{};
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const SceneObject& o = scene.objects[i];
    const Shape& shape = *objectShapes_[i];
    DrawItem item;
    item.objectIndex = static_cast<int>(i);
    item.mesh = shape.gpu.get();
    item.field = shape.field;
    item.model = modelMatrix(o, shape.localBounds);
    item.normalMatrix = glm::transpose(glm::inverse(glm::mat3(item.model)));
    item.albedo = o.albedo;
    items_.push_back(item);
    if (shape.localBounds.empty()) continue;  // a field not attached yet
    for (int c = 0; c < 8; ++c) {
      const glm::vec3 corner((c & 1) ? shape.localBounds.max.x : shape.localBounds.min.x,
                             (c & 2) ? shape.localBounds.max.y : shape.localBounds.min.y,
                             (c & 4) ? shape.localBounds.max.z : shape.localBounds.min.z);
      const glm::vec3 world(item.model * glm::vec4(corner, 1.0f));
      items_.back().worldBounds.extend(world);
      bounds_.extend(world);
      if (o.shape != ShapeKind::Plane) casterBounds_.extend(world);
    }
  }
}

void SceneGeometry::attachField(int objectIndex, const geometry::GpuDualContouring* field,
                                const geometry::Aabb& localBounds) {
  Shape& shape = *objectShapes_.at(static_cast<std::size_t>(objectIndex));
  shape.field = field;
  shape.localBounds = localBounds;
}

std::size_t SceneGeometry::triangleCount() const {
  std::size_t n = 0;
  for (const DrawItem& item : items_)
    if (item.mesh) n += item.mesh->triangleCount();
  return n;
}

std::size_t SceneGeometry::bytes() const {
  std::size_t n = 0;
  for (const auto& [key, shape] : shapes_)
    if (shape.gpu) n += shape.gpu->bytes();
  return n;
}

void DrawItem::draw(int instances) const {
  if (mesh) mesh->draw(instances);
  if (field) field->draw(instances);
}

}  // namespace tallow::sss
