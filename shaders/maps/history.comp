#version 450 core
// Before a frame's gather after the geometry or a light moved (sss.history > 0): each map texel's
// accumulated sum is kept, trimmed or reset by sssHistoryScale (maps/history.glsl), comparing the
// maps' G-buffer of the last frame with this frame's. What is kept goes to uHistory as a mean and
// its frames (rgb: mean of B, a: frames kept; 0 where reset), and the maps are emptied for this
// frame's estimate alone; maps/history_merge.comp adds the two back together (rescaled with
// sss.history_rescale). Texels with no surface now are reset, so no stale sum reaches the mipmaps.
#include "maps/covered_texels.glsl"
#include "maps/history.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

uniform sampler2DArray uOldPosition;  // xyz: x_o [m], w: slot + 1 (0: no surface)
uniform sampler2DArray uOldNormal;
uniform sampler2DArray uNewPosition;
uniform sampler2DArray uNewNormal;
uniform float uHistoryFrames;  // sss.history
uniform float uMaxMove;        // [m]
uniform float uMinCos;
layout(rgba32f, binding = 0) uniform image2DArray uMaps;
layout(rgba32f, binding = 1) writeonly uniform image2DArray uHistory;

void main() {
  ivec3 id = historyTexel(imageSize(uMaps));
  if (id.x < 0 || any(greaterThanEqual(id, imageSize(uMaps)))) return;
  vec4 m = imageLoad(uMaps, id);
  vec4 o = texelFetch(uOldPosition, id, 0);
  vec4 n = texelFetch(uNewPosition, id, 0);
  float s = sssHistoryScale(o.xyz, o.w, texelFetch(uOldNormal, id, 0).xyz, n.xyz, n.w,
                            texelFetch(uNewNormal, id, 0).xyz, m.a, uHistoryFrames, uMaxMove, uMinCos);
  float kept = s * m.a;
  imageStore(uHistory, id, kept > 0.0 ? vec4(m.rgb / m.a, kept) : vec4(0.0));
  imageStore(uMaps, id, vec4(0.0));
}
