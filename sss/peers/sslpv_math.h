#pragma once
// The CPU side of SSLPV (Børlum et al. 2011, "the paper"; docs/sslpv.md): the shared spherical-
// harmonics and material-volume files (shaders/peers/sslpv/sh.glsl, shaders/peers/sslpv/volume.glsl) compiled
// as C++ in namespace tallow::sss::sslpv_glsl, the propagation matrices of §4, and the LPV grid's
// placement around the translucent objects.
#include <glm/glm.hpp>

#include <array>
#include <cstdint>

#include "geometry/triangle_mesh.h"
#include "gpu/glsl_shared.h"  // TALLOW_FN and GLM's GLSL vocabulary; no OpenGL

namespace tallow::sss::sslpv_glsl {
using namespace glm;
using uint = std::uint32_t;  // GLSL's uint: 32-bit, wrapping modulo 2³²
#include "shaders/peers/sslpv/sh.glsl"
#include "shaders/peers/sslpv/volume.glsl"
}  // namespace tallow::sss::sslpv_glsl

namespace tallow::sss {

/// Upper bound of sslpv.grid (cells per axis): the voxelisation's parity images grow as
/// (2N)² × 3 × 2N/32 words per translucent object.
inline constexpr int kMaxSslpvGrid = 128;

/// The six neighbours a destination cell gathers from, as offsets source − destination, in the
/// order of sslpvPropagationMatrices and shaders/peers/sslpv/propagate.comp: +x, −x, +y, −y, +z, −z.
std::array<glm::ivec3, 6> sslpvNeighbourOffsets();

/// Σ'_f M_{f,d←s} of §4 for each neighbour s = d + offset (sslpvNeighbourOffsets): the summed
/// face-flux matrices of a unit cubic cell, M_{f,d←s} = (1/π ∫_{2π} n_f·ω y_lm dω)(∫_{Δω_{f,s}} y_l'm' dω),
/// over the five faces f of d other than the one it shares with s. The face integrals are exact:
/// the solid angle of each face seen from s's centre (Van Oosterom and Strackee 1983) and its
/// vector solid angle ∫ ω dω = ½ Σ_edges Θ_e u_e (Arvo 1995). Column-major as GLSL's mat4: the
/// destination's coefficients are M · c_s.
std::array<glm::mat4, 6> sslpvPropagationMatrices();

/// ∫_Ω y_lm(ω) dω over the solid angle Ω of the planar convex polygon `corners` (in order around
/// it) seen from `eye`: (Y0 Ω, Y1 W_y, Y1 W_z, Y1 W_x) with W = ∫_Ω ω dω. For the tests.
glm::dvec4 sslpvPolygonProjection(const glm::dvec3& eye, const glm::dvec3* corners, int count);

/// The LPV grid: an axis-aligned cube of `size`³ cubic cells of width `cell` [m] from `origin`.
struct SslpvGrid {
  glm::vec3 origin{0.0f};
  float cell = 0.0f;
  int size = 0;
  float side() const { return cell * static_cast<float>(size); }
  float cellMm() const { return cell * 1000.0f; }
};

/// The cube of `size`³ cells centred on `box` whose side is the box's largest extent (cubic cells:
/// the propagation matrices assume them). An empty or flat box gets a side of 1 mm at least.
SslpvGrid fitSslpvGrid(const geometry::Aabb& box, int size);

}  // namespace tallow::sss
