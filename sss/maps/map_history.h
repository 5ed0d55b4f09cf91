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

/// sss.history_rescale: the mip level of the maps whose footprint (2^level texels) is nearest to
/// `diffusionLengths` times the shortest diffusion length, on maps of `mapSize` texels spanning
/// `spanMm`; the coarse scale on which a kept history is rescaled to this frame's estimate
/// (sssHistoryRescale). At least kHistoryRescaleMinLevel, at most log2(mapSize).
int historyRescaleLevel(int mapSize, double spanMm, double shortestDiffusionMm, double diffusionLengths);

/// The finest level the ratio is taken on: 8×8 texels. On fewer this frame's N samples a texel
/// leave the ratio so noisy that its shrinkage (sssHistoryRescale) keeps much of the lag: the slab
/// whose light turned 60° (MapHistory.TheKeptHistoryFollowsALightThatTurnsWhileTheSurfaceHolds)
/// kept 25% of it on level 1 with N = 8.
inline constexpr int kHistoryRescaleMinLevel = 3;

/// Beyond this ratio of this frame's coarse mean to the history's (or under its inverse) a texel's
/// history is dropped rather than rescaled: the light changed more than a lag can be corrected.
inline constexpr float kHistoryMaxRatio = 4.0f;

}  // namespace tallow::sss
