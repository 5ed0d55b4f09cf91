#include "sss/peers/sslpv_math.h"

#include <algorithm>
#include <cmath>

namespace tallow::sss {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// Solid angle of the triangle (a, b, c) seen from the origin (Van Oosterom and Strackee 1983):
/// tan(Ω/2) = |a·(b×c)| / (|a||b||c| + (a·b)|c| + (a·c)|b| + (b·c)|a|).
double triangleSolidAngle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
  const double numerator = std::abs(glm::dot(a, glm::cross(b, c)));
  const double denominator = la * lb * lc + glm::dot(a, b) * lc + glm::dot(a, c) * lb + glm::dot(b, c) * la;
  return 2.0 * std::atan2(numerator, denominator);
}

}  // namespace

std::array<glm::ivec3, 6> sslpvNeighbourOffsets() {
  return {glm::ivec3(1, 0, 0), glm::ivec3(-1, 0, 0), glm::ivec3(0, 1, 0),
          glm::ivec3(0, -1, 0), glm::ivec3(0, 0, 1), glm::ivec3(0, 0, -1)};
}

glm::dvec4 sslpvPolygonProjection(const glm::dvec3& eye, const glm::dvec3* corners, int count) {
  double omega = 0.0;
  glm::dvec3 w(0.0), centre(0.0);
  for (int i = 0; i < count; ++i) centre += corners[i] - eye;
  for (int i = 1; i + 1 < count; ++i) omega += triangleSolidAngle(corners[0] - eye, corners[i] - eye, corners[i + 1] - eye);
  // ∫_Ω ω dω = ½ Σ_e Θ_e u_e (Arvo 1995, the irradiance vector of a polygon of unit radiance): Θ_e
  // the angle an edge subtends, u_e the unit normal of the plane through it and the eye, all edges
  // turning the same way; the sign is fixed so that the result points at the polygon.
  for (int i = 0; i < count; ++i) {
    const glm::dvec3 a = glm::normalize(corners[i] - eye), b = glm::normalize(corners[(i + 1) % count] - eye);
    const glm::dvec3 n = glm::cross(a, b);
    const double len = glm::length(n);
    if (len <= 0.0) continue;
    w += std::atan2(len, glm::dot(a, b)) * (n / len);
  }
  w *= 0.5;
  if (glm::dot(w, centre) < 0.0) w = -w;
  const double y0 = sslpv_glsl::SSLPV_Y0, y1 = sslpv_glsl::SSLPV_Y1;
  return {y0 * omega, y1 * w.y, y1 * w.z, y1 * w.x};
}

std::array<glm::mat4, 6> sslpvPropagationMatrices() {
  std::array<glm::mat4, 6> out{};
  const auto offsets = sslpvNeighbourOffsets();
  for (int s = 0; s < 6; ++s) {
    const glm::dvec3 source(offsets[s]);  // the source cell's centre; the destination's is the origin
    glm::dmat4 m(0.0);
    for (int axis = 0; axis < 3; ++axis)
      for (int sign = -1; sign <= 1; sign += 2) {
        glm::dvec3 normal(0.0);
        normal[axis] = sign;
        if (normal == source) continue;  // the face d shares with s
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        glm::dvec3 corners[4];
        for (int k = 0; k < 4; ++k) {
          corners[k][axis] = 0.5 * sign;
          corners[k][u] = (k == 1 || k == 2) ? 0.5 : -0.5;
          corners[k][v] = (k >= 2) ? 0.5 : -0.5;
        }
        // Flux through the face, v_f^T c_s, re-emitted as a cosine lobe about n_f (§3.2, §4).
        const glm::dvec4 flux = sslpvPolygonProjection(source, corners, 4);
        const glm::dvec4 lobe(sslpv_glsl::sslpvCosineLobe(glm::vec3(normal)));
        for (int col = 0; col < 4; ++col)
          for (int row = 0; row < 4; ++row) m[col][row] += lobe[row] * flux[col];
      }
    out[static_cast<std::size_t>(s)] = glm::mat4(m);
  }
  return out;
}

SslpvGrid fitSslpvGrid(const geometry::Aabb& box, int size) {
  SslpvGrid g;
  g.size = std::max(size, 1);
  constexpr float kMinSide = 1e-3f;  // metres; a flat or empty box still gets cells
  const glm::vec3 extent = box.empty() ? glm::vec3(0.0f) : box.size();
  const float side = std::max({extent.x, extent.y, extent.z, kMinSide});
  const glm::vec3 centre = box.empty() ? glm::vec3(0.0f) : box.centre();
  g.cell = side / static_cast<float>(g.size);
  g.origin = centre - glm::vec3(0.5f * side);
  return g;
}

}  // namespace tallow::sss
