// Reusing a scattered radiosity map texel's history while the geometry deforms or the lights move
// (issue 17, point 3), in the GLSL/C++ subset of common/shared.glsl: shaders/maps/history.comp runs
// it per map texel before the frame's gather, sss/maps/map_history.h compiles the same lines for the
// tests. Documentation: docs/radiosity-maps.md, "History while the geometry moves".
//
// The maps' views stay while the objects' bounding sphere stays inside the one they were made for,
// so a texel is the same ray before and after the change; what moves is the surface point on it.
// Where the point moved by at most `maxMove` (sss.history_move times the shortest diffusion length
// 1/σ_tr: B changes on the scale of 1/σ_tr) on the same object, and its normal turned by less than
// acos(minCos), the texel's sum (rgb: Σ of B over its frames, a: the frames) is kept, scaled down
// to at most history − 1 frames so that with this frame's estimate it holds at most `history`: a
// mean over the last frames, which follows the moving surface and light with a lag of about
// history/2 frames. Elsewhere (the surface moved, appeared or left the texel) it starts again.
#include "common/shared.glsl"

// The factor for the texel's accumulated sum before this frame's estimate is added: 0 resets it,
// 1 keeps it whole, (history − 1)/frames trims it to history − 1 frames. Slots are the G-buffer's
// object tags (slot + 1; 0: no surface).
TALLOW_FN float sssHistoryScale(vec3 oldPosition, float oldSlot, vec3 oldNormal, vec3 newPosition, float newSlot,
                                vec3 newNormal, float frames, float history, float maxMove, float minCos) {
  if (history < 1.0f || frames <= 0.0f) return 0.0f;
  if (newSlot < 0.5f || abs(newSlot - oldSlot) > 0.5f) return 0.0f;
  if (length(newPosition - oldPosition) > maxMove) return 0.0f;
  if (dot(oldNormal, newNormal) < minCos * length(oldNormal) * length(newNormal)) return 0.0f;
  float keep = history - 1.0f;
  return frames > keep ? keep / frames : 1.0f;
}

// sss.history_rescale: the kept history is a mean over earlier frames, so where the light reaching
// a texel changed while its surface point held (the candle's flame sinks with its cup, about 0.5 mm
// a frame at 4 fps, while the wall it lights stands still) the mean lags behind, and a lag is a
// bias that more frames do not remove (RESULTS: the candle's lower wall 20% dark with 8 frames kept).
// So the history is rescaled, band by band, by how much this frame's estimate changed on a coarse
// scale: the ratio of this frame's mean to the history's mean over the same texels (those that kept
// a history) in a coarse mip level's footprint, a fraction of a diffusion length across. That ratio
// is itself noisy (this frame's N samples a texel, averaged over the footprint), and where the light
// barely changed, following it only adds this frame's noise back; so the ratio's change is shrunk by
// c = Δ² / (Δ² + σ²) (Δ: the change of the bands' mean, σ²: its variance, from the footprint's mean
// squared difference between this frame and the history per texel over the texels in it — the mip
// level's averages over a partly covered footprint scale both by the same fraction, which cancels).
// A ratio beyond [1/maxRatio, maxRatio], or a band with light in one mean and none in the other, is
// a change the history cannot follow: the texel starts again.
// Returns the per-band factor in rgb and 1 in a to keep the history, (1, 1, 1, 0) to reset it.
TALLOW_FN vec4 sssHistoryRescale(vec3 freshCoarse, vec3 historyCoarse, float meanSquaredDifference, float texels,
                                 float maxRatio) {
  vec4 r = vec4(1.0f, 1.0f, 1.0f, 1.0f);
  for (int c = 0; c < 3; ++c) {
    float f = freshCoarse[c], h = historyCoarse[c];
    if (!(f > 0.0f) && !(h > 0.0f)) continue;  // no light in this band either way
    if (!(f > 0.0f) || !(h > 0.0f)) return vec4(1.0f, 1.0f, 1.0f, 0.0f);
    float ratio = f / h;
    if (!(ratio <= maxRatio) || !(ratio * maxRatio >= 1.0f)) return vec4(1.0f, 1.0f, 1.0f, 0.0f);
    r[c] = ratio;
  }
  float meanFresh = (freshCoarse.x + freshCoarse.y + freshCoarse.z) / 3.0f;
  float meanHistory = (historyCoarse.x + historyCoarse.y + historyCoarse.z) / 3.0f;
  if (!(meanHistory > 0.0f)) return r;
  float change = meanFresh / meanHistory - 1.0f;
  float variance = max(meanSquaredDifference, 0.0f) / (max(texels, 1.0f) * meanHistory * meanHistory);
  float shrink = change * change > 0.0f ? change * change / (change * change + variance) : 0.0f;
  return vec4(vec3(1.0f) + (vec3(r) - vec3(1.0f)) * shrink, 1.0f);
}
