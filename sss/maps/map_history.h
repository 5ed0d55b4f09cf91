#pragma once
// sss.history (issue 17, point 3): when the geometry deforms or a light moves, each scattered
// radiosity map texel keeps, trims or resets its accumulated estimate by shaders/maps/history.glsl,
// compiled here as C++ for the tests (history_glsl::sssHistoryScale), and the tolerances it is run with.
#include <glm/glm.hpp>

#include "gpu/glsl_shared.h"  // TALLOW_FN and GLM's GLSL vocabulary; no OpenGL
#include "sss/scene.h"

namespace tallow::sss {

namespace history_glsl {
using namespace glm;
#include "shaders/maps/history.glsl"
}  // namespace history_glsl

/// The shortest diffusion length 1/σ_tr [mm] over the translucent objects' materials and bands
/// (1e300 when there are none).
double shortestDiffusionLengthMm(const Scene& scene);

/// How far a map texel's surface point may move [m] and how far its normal may turn (cosine) for the
/// texel to keep its history: `diffusionLengths` (sss.history_move) times the shortest 1/σ_tr, since
/// B at x_o changes on the scale of the diffusion length; 25°.
struct HistoryTolerance {
  float maxMoveM = 0.0f;
  float minCos = 0.0f;
};
HistoryTolerance historyTolerance(const Scene& scene, double diffusionLengths);

}  // namespace tallow::sss
