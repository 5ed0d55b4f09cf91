#version 450 core
// A still after motion (sss.history > 0, sss/maps/radiosity_maps.h): uFrom holds what the maps held
// when the still started (rgb: Σ B, a: frames, the kept history's and the last moving frame's).
// Each of the still's first D = sss.frames frames, after its fresh samples are added, takes
// uFrom / D away, so after n frames the maps hold the n fresh frames plus (1 − n/D) of what was
// kept: its weight fades linearly to nothing, and at n = D the maps are the n fresh frames alone —
// what a restart at the pause accumulates with the same seeds.
layout(local_size_x = 8, local_size_y = 8) in;

// Over the texels the last moving frame's merge listed (uCompacted), where all of uFrom lies, or
// over every texel.
#include "maps/covered_texels.glsl"

uniform float uShare;  // 1 / D
layout(rgba32f, binding = 0) uniform image2DArray uMaps;
layout(rgba32f, binding = 1) readonly uniform image2DArray uFrom;

void main() {
  ivec3 id = historyTexel(imageSize(uMaps));
  if (id.x < 0 || any(greaterThanEqual(id, imageSize(uMaps)))) return;
  vec4 from = imageLoad(uFrom, id);
  if (from.a <= 0.0) return;
  vec4 m = imageLoad(uMaps, id) - uShare * from;
  // Rounding may leave a sum a hair below 0 where the fresh frames hold nothing.
  imageStore(uMaps, id, max(m, vec4(0.0)));
}
