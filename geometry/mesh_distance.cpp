#include "geometry/mesh_distance.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace tallow::geometry {

double pointTriangleDistance(glm::dvec3 p, glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
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

TriangleGrid::TriangleGrid(const TriangleMesh& mesh, double bucketSize) : mesh_(mesh), bucket_(bucketSize) {
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

double TriangleGrid::distance(glm::dvec3 p, double cap) const {
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

}  // namespace tallow::geometry
