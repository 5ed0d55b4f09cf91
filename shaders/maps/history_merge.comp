#version 450 core
// After a frame's gather on a history reuse (sss.history > 0): the kept history (uHistory, from
// maps/history.comp: rgb the mean of B over its frames, a the frames) and this frame's estimate
// (uMaps: rgb the sum of B, a its frames, 1 where the gather drew) are added back into one sum.
//   uStage 0 (only with sss.history_rescale): uFresh = this frame's mean (rgb) and its squared
//            difference from the history's mean (a, bands averaged) where the texel kept a
//            history, 0 elsewhere, so that its mipmaps and uHistory's average the same texels.
//   uStage 1: uMaps = history mean · ratio · frames kept + this frame's sum, the ratio from
//            sssHistoryRescale (maps/history.glsl) on both at mip level uLevel (1 without rescale).
#include "maps/covered_texels.glsl"
#include "maps/history.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

uniform int uStage;
uniform bool uRescale;
uniform float uLevel;     // the coarse mip level of the ratio
uniform float uMaxRatio;  // beyond it (or under its inverse) the texel starts again
uniform sampler2DArray uHistoryMips;
uniform sampler2DArray uFreshMips;
layout(rgba32f, binding = 0) uniform image2DArray uMaps;
layout(rgba32f, binding = 1) readonly uniform image2DArray uHistory;
layout(rgba32f, binding = 2) writeonly uniform image2DArray uFresh;

void main() {
  ivec3 size = imageSize(uMaps);
  ivec3 id = historyTexel(size);
  if (id.x < 0 || any(greaterThanEqual(id, size))) return;
  vec4 fresh = imageLoad(uMaps, id);
  vec4 history = imageLoad(uHistory, id);
  bool both = history.a > 0.0 && fresh.a > 0.0;
  if (uStage == 0) {
    vec3 mean = fresh.rgb / fresh.a;
    float d = dot(mean - history.rgb, vec3(1.0 / 3.0));
    imageStore(uFresh, id, both ? vec4(mean, d * d) : vec4(0.0));
    return;
  }
  if (!both) return;  // reset (or no surface now): this frame's estimate alone
  vec4 ratio = vec4(1.0);
  if (uRescale) {
    vec3 uv = vec3((vec2(id.xy) + 0.5) / vec2(size.xy), float(id.z));
    vec4 freshCoarse = textureLod(uFreshMips, uv, uLevel);
    ratio = sssHistoryRescale(freshCoarse.rgb, textureLod(uHistoryMips, uv, uLevel).rgb, freshCoarse.a,
                              exp2(2.0 * uLevel), uMaxRatio);
  }
  if (ratio.a > 0.0) imageStore(uMaps, id, vec4(history.rgb * ratio.rgb * history.a + fresh.rgb, history.a + fresh.a));
}
