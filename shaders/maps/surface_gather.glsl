// The no-cache method's part of the camera pass (camera/surface_method.glsl): the gather per pixel
// against the light G-buffers (the paper's Fig. 11), a new estimate every frame (map index 4095
// keeps its random streams apart from the maps').
#include "camera/surface_method.glsl"
#include "maps/gather.glsl"

TranslucentShading translucentShading(vec3 xo, vec3 facing, vec3 dpdx, vec3 dpdy, int slot) {
  return shadingOf(gatherScatteredRadiosity(xo, facing, uvec2(gl_FragCoord.xy), 4095, slot));
}

vec3 surroundingsIrradiance(vec3 p, vec3 n) { return vec3(0.0); }
