// The radiosity maps' part of the camera pass (camera/surface_method.glsl): B by Algorithm 1 over
// the maps, and the VPLs' light on the surroundings (Eq. 15).
#include "camera/surface_method.glsl"
#include "maps/algorithm1.glsl"
#include "maps/vpl_receiver.glsl"

TranslucentShading translucentShading(vec3 xo, vec3 facing, vec3 dpdx, vec3 dpdy, int slot) {
  TranslucentShading s;
  int firstMap = -1, secondFacingMap = -1;
  s.b = scatteredRadiosity(xo, facing, dpdx, dpdy, s.seenBy, firstMap, secondFacingMap);
  s.coverageBins = uvec2(coverageBin(firstMap), coverageBin(secondFacingMap)) + 1u;
  return s;
}

vec3 surroundingsIrradiance(vec3 p, vec3 n) { return vplIrradiance(p, n); }
