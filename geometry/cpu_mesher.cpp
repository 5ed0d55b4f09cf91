#include "geometry/cpu_mesher.h"

#include "geometry/openvdb_support.h"

#include <openvdb/openvdb.h>
#include <openvdb/tools/VolumeToMesh.h>

#include <cmath>
#include <limits>

namespace tallow::geometry {

namespace {

/// Samples equal to the background are inactive and skipped by the mesher, so the background is
/// a value the lattice never holds; it is positive (outside), closing nothing inside the lattice.
constexpr float kBackground = std::numeric_limits<float>::max();

openvdb::FloatGrid::Ptr toGrid(const SampledLattice& lattice) {
  auto grid = openvdb::FloatGrid::create(kBackground);
  auto transform = openvdb::math::Transform::createLinearTransform(lattice.cellSize);
  transform->postTranslate(openvdb::Vec3d(lattice.origin.x, lattice.origin.y, lattice.origin.z));
  grid->setTransform(transform);
  auto accessor = grid->getAccessor();
  const int n = lattice.n;
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) accessor.setValue(openvdb::Coord(x, y, z), lattice.at(x, y, z));
  return grid;
}

double lengthSquared(const glm::vec3& a, const glm::vec3& b) {
  const glm::dvec3 d = glm::dvec3(a) - glm::dvec3(b);
  return glm::dot(d, d);
}

}  // namespace

TriangleMesh meshOnCpu(const SampledLattice& lattice, const ScalarField& field) {
  initialiseOpenVdb();
  const auto grid = toGrid(lattice);
  std::vector<openvdb::Vec3s> points;
  std::vector<openvdb::Vec3I> triangles;
  std::vector<openvdb::Vec4I> quads;
  openvdb::tools::volumeToMesh(*grid, points, triangles, quads, /*isovalue=*/0.0, /*adaptivity=*/0.0);

  TriangleMesh mesh;
  mesh.positions.reserve(points.size());
  for (const auto& p : points) mesh.positions.emplace_back(p.x(), p.y(), p.z());

  // OpenVDB's primitives are already counter-clockwise seen from the positive (outside) side;
  // tests/fields_test.cpp checks this (signed volume > 0, winding agrees with the gradient).
  mesh.triangles.reserve(triangles.size() + 2 * quads.size());
  for (const auto& t : triangles) mesh.triangles.push_back({t[0], t[1], t[2]});
  for (const auto& q : quads) {
    // Split along the shorter diagonal: the better-shaped pair of triangles.
    if (lengthSquared(mesh.positions[q[0]], mesh.positions[q[2]]) <=
        lengthSquared(mesh.positions[q[1]], mesh.positions[q[3]])) {
      mesh.triangles.push_back({q[0], q[1], q[2]});
      mesh.triangles.push_back({q[0], q[2], q[3]});
    } else {
      mesh.triangles.push_back({q[0], q[1], q[3]});
      mesh.triangles.push_back({q[1], q[2], q[3]});
    }
  }

  mesh.normals.resize(mesh.positions.size());
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const glm::dvec3 g = field.gradient(glm::dvec3(mesh.positions[i]));
    const double len = glm::length(g);
    mesh.normals[i] = (len > 0.0 && std::isfinite(len)) ? glm::vec3(g / len) : glm::vec3(0, 1, 0);
  }
  return mesh;
}

TriangleMesh meshOnCpu(const ScalarField& field, int n) { return meshOnCpu(sampleField(field, n), field); }

}  // namespace tallow::geometry
