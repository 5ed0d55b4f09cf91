#pragma once
// Quality measures of triangle meshes shared by the geometry tests: enclosed volume, area, face
// normals, edge use (watertightness), connected components and the Hausdorff distance between two
// meshes (point-to-triangle distances through a uniform bucket grid).
#include <glm/glm.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numeric>
#include <utility>
#include <vector>

#include "geometry/scalar_field.h"
#include "geometry/triangle_mesh.h"

namespace tallow::test {

/// Signed enclosed volume by the divergence theorem: Σ a·(b×c) / 6 (> 0 for outward winding).
inline double signedVolume(const geometry::TriangleMesh& mesh) {
  double v = 0.0;
  for (const auto& t : mesh.triangles)
    v += glm::dot(glm::dvec3(mesh.positions[t[0]]),
                  glm::cross(glm::dvec3(mesh.positions[t[1]]), glm::dvec3(mesh.positions[t[2]])));
  return v / 6.0;
}

/// (b − a) × (c − a): the face normal by the winding, length twice the area.
inline glm::dvec3 faceCross(const geometry::TriangleMesh& mesh, const std::array<std::uint32_t, 3>& t) {
  const glm::dvec3 a(mesh.positions[t[0]]), b(mesh.positions[t[1]]), c(mesh.positions[t[2]]);
  return glm::cross(b - a, c - a);
}

/// How many triangles use each undirected edge.
inline std::map<std::pair<std::uint32_t, std::uint32_t>, int> edgeUses(const geometry::TriangleMesh& mesh) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
  for (const auto& t : mesh.triangles)
    for (std::size_t i = 0; i < 3; ++i) ++uses[std::minmax(t[i], t[(i + 1) % 3])];
  return uses;
}

/// Number of undirected edges not used by exactly two triangles (0 for a watertight mesh).
inline int badEdges(const geometry::TriangleMesh& mesh) {
  int bad = 0;
  for (const auto& [edge, n] : edgeUses(mesh)) bad += n == 2 ? 0 : 1;
  return bad;
}

/// Connected components of the triangles (sharing a vertex joins them), by union-find.
inline int countComponents(const geometry::TriangleMesh& mesh) {
  std::vector<std::uint32_t> parent(mesh.positions.size());
  std::iota(parent.begin(), parent.end(), 0u);
  auto find = [&](std::uint32_t v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  std::vector<bool> used(mesh.positions.size(), false);
  for (const auto& t : mesh.triangles) {
    for (std::uint32_t v : t) used[v] = true;
    parent[find(t[1])] = find(t[0]);
    parent[find(t[2])] = find(t[0]);
  }
  int count = 0;
  for (std::uint32_t v = 0; v < parent.size(); ++v) count += (used[v] && find(v) == v) ? 1 : 0;
  return count;
}

/// Total area of the triangles.
inline double surfaceArea(const geometry::TriangleMesh& mesh) {
  double area = 0.0;
  for (const auto& t : mesh.triangles) area += 0.5 * glm::length(faceCross(mesh, t));
  return area;
}

/// Distance from p to the closed triangle abc (closest point by Voronoi regions, after Ericson,
/// Real-Time Collision Detection §5.1.5); degenerate triangles fall out as segments or points.
inline double pointTriangleDistance(glm::dvec3 p, glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
  const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) return glm::length(ap);  // vertex a
  const glm::dvec3 bp = p - b;
  const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return glm::length(bp);  // vertex b
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return glm::length(p - (a + (d1 / (d1 - d3)) * ab));  // edge ab
  const glm::dvec3 cp = p - c;
  const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return glm::length(cp);  // vertex c
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return glm::length(p - (a + (d2 / (d2 - d6)) * ac));  // edge ac
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
    return glm::length(p - (b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b)));  // edge bc
  const double denom = va + vb + vc;
  if (!(std::abs(denom) > 0.0)) {  // zero-area triangle not caught above: nearest of its edges
    auto segment = [&](glm::dvec3 s, glm::dvec3 e) {
      const glm::dvec3 d = e - s;
      const double l2 = glm::dot(d, d);
      const double u = l2 > 0.0 ? std::clamp(glm::dot(p - s, d) / l2, 0.0, 1.0) : 0.0;
      return glm::length(p - (s + u * d));
    };
    return std::min({segment(a, b), segment(b, c), segment(c, a)});
  }
  return glm::length(p - (a + ab * (vb / denom) + ac * (vc / denom)));  // inside the face
}

/// A mesh's triangles bucketed in a uniform grid of cubic cells (each triangle in every cell its
/// bounding box overlaps), for nearest-surface queries: distance() searches shells of cells around
/// the query point and stops once no unsearched cell can hold anything closer.
class TriangleGrid {
 public:
  /// `bucketSize` > 0 in world units; about the triangles' size is best (e.g. the lattice cell).
  TriangleGrid(const geometry::TriangleMesh& mesh, double bucketSize) : mesh_(mesh), bucket_(bucketSize) {
    glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    for (const auto& t : mesh.triangles)
      for (std::uint32_t v : t) {
        lo = glm::min(lo, glm::dvec3(mesh.positions[v]));
        hi = glm::max(hi, glm::dvec3(mesh.positions[v]));
      }
    if (mesh.triangles.empty()) lo = hi = glm::dvec3(0.0);
    // Never more than 512 cells per axis, whatever bucketSize was asked for.
    bucket_ = std::max(bucket_, std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z}) / 512.0);
    if (!(bucket_ > 0.0)) bucket_ = 1.0;
    origin_ = lo;
    for (int a = 0; a < 3; ++a) dims_[a] = static_cast<int>(std::floor((hi[a] - lo[a]) / bucket_)) + 1;
    std::vector<std::uint32_t> counts(cellCount() + 1, 0);
    auto forCells = [&](const std::array<std::uint32_t, 3>& t, auto&& visit) {
      glm::ivec3 c0(std::numeric_limits<int>::max()), c1(std::numeric_limits<int>::min());
      for (std::uint32_t v : t) {
        const glm::ivec3 c = cellOf(glm::dvec3(mesh_.positions[v]));
        c0 = glm::min(c0, c);
        c1 = glm::max(c1, c);
      }
      for (int z = c0.z; z <= c1.z; ++z)
        for (int y = c0.y; y <= c1.y; ++y)
          for (int x = c0.x; x <= c1.x; ++x) visit(flat(x, y, z));
    };
    for (const auto& t : mesh.triangles) forCells(t, [&](std::size_t cell) { ++counts[cell + 1]; });
    std::partial_sum(counts.begin(), counts.end(), counts.begin());
    start_ = counts;
    items_.resize(counts.back());
    for (std::uint32_t i = 0; i < mesh.triangles.size(); ++i)
      forCells(mesh.triangles[i], [&](std::size_t cell) { items_[counts[cell]++] = i; });
  }

  /// Distance from p to the nearest triangle, or `cap` when none is closer than cap.
  double distance(glm::dvec3 p, double cap) const {
    double best = cap;
    const glm::ivec3 c(glm::floor((p - origin_) / bucket_));
    const int maxShell = static_cast<int>(std::ceil(cap / bucket_)) + 1;
    for (int r = 0; r <= maxShell; ++r) {
      // Every cell of shell r or beyond is at least r − 1 buckets from p (p lies in cell c).
      if (r > 0 && best <= (r - 1) * bucket_) break;
      const glm::ivec3 lo = glm::max(c - r, glm::ivec3(0)), hi = glm::min(c + r, glm::ivec3(dims_[0], dims_[1], dims_[2]) - 1);
      for (int z = lo.z; z <= hi.z; ++z)
        for (int y = lo.y; y <= hi.y; ++y)
          for (int x = lo.x; x <= hi.x; ++x) {
            const bool onShell = std::abs(x - c.x) == r || std::abs(y - c.y) == r || std::abs(z - c.z) == r;
            if (!onShell) continue;
            const std::size_t cell = flat(x, y, z);
            for (std::uint32_t k = start_[cell]; k < start_[cell + 1]; ++k) {
              const auto& t = mesh_.triangles[items_[k]];
              best = std::min(best, pointTriangleDistance(p, glm::dvec3(mesh_.positions[t[0]]),
                                                          glm::dvec3(mesh_.positions[t[1]]),
                                                          glm::dvec3(mesh_.positions[t[2]])));
            }
          }
    }
    return best;
  }

 private:
  glm::ivec3 cellOf(glm::dvec3 p) const {
    const glm::ivec3 c(glm::floor((p - origin_) / bucket_));
    return glm::clamp(c, glm::ivec3(0), glm::ivec3(dims_[0], dims_[1], dims_[2]) - 1);
  }
  std::size_t cellCount() const {
    return static_cast<std::size_t>(dims_[0]) * static_cast<std::size_t>(dims_[1]) * static_cast<std::size_t>(dims_[2]);
  }
  std::size_t flat(int x, int y, int z) const {
    return static_cast<std::size_t>(x) +
           static_cast<std::size_t>(dims_[0]) * (static_cast<std::size_t>(y) + static_cast<std::size_t>(dims_[1]) * static_cast<std::size_t>(z));
  }

  const geometry::TriangleMesh& mesh_;
  double bucket_;
  glm::dvec3 origin_{0.0};
  std::array<int, 3> dims_{1, 1, 1};
  std::vector<std::uint32_t> start_, items_;  ///< CSR: triangles of cell i are items_[start_[i] .. start_[i + 1])
};

/// Largest distance from a vertex used by `from`'s triangles to the surface of `to` (capped at
/// `cap`): the one-sided Hausdorff distance with vertices standing for the surface of `from`.
inline double directedHausdorff(const geometry::TriangleMesh& from, const geometry::TriangleMesh& to, double bucketSize,
                                double cap) {
  const TriangleGrid grid(to, bucketSize);
  std::vector<bool> used(from.positions.size(), false);
  for (const auto& t : from.triangles)
    for (std::uint32_t v : t) used[v] = true;
  double worst = 0.0;
  for (std::size_t v = 0; v < from.positions.size(); ++v)
    if (used[v]) worst = std::max(worst, grid.distance(glm::dvec3(from.positions[v]), cap));
  return worst;
}

/// Symmetric Hausdorff distance between two meshes (vertex-to-surface both ways), capped at `cap`.
inline double hausdorffDistance(const geometry::TriangleMesh& a, const geometry::TriangleMesh& b, double bucketSize,
                                double cap) {
  return std::max(directedHausdorff(a, b, bucketSize, cap), directedHausdorff(b, a, bucketSize, cap));
}

/// value = ‖p − centre‖ − r: the exact case, a true signed distance, so |value| is the distance to
/// the surface. Bounds: the given box, or a 20% margin around the sphere.
class SphereField final : public geometry::ScalarField {
 public:
  SphereField(glm::dvec3 centre, double radius) : SphereField(centre, radius, margin(centre, radius)) {}
  SphereField(glm::dvec3 centre, double radius, geometry::Aabb box) : centre_(centre), radius_(radius), box_(box) {}
  double value(glm::dvec3 p) const override { return glm::length(p - centre_) - radius_; }
  glm::dvec3 gradient(glm::dvec3 p) const override { return glm::normalize(p - centre_); }
  geometry::Aabb bounds() const override { return box_; }

 private:
  static geometry::Aabb margin(glm::dvec3 centre, double radius) {
    geometry::Aabb box;
    box.extend(glm::vec3(centre - 1.2 * radius));
    box.extend(glm::vec3(centre + 1.2 * radius));
    return box;
  }
  glm::dvec3 centre_;
  double radius_;
  geometry::Aabb box_;
};

}  // namespace tallow::test
