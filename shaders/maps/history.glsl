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
