// The radiosity maps' part of the camera pass (camera/surface_method.glsl): B by Algorithm 1 over
// the maps; the VPLs' light on the surroundings (Eq. 15) only in the variant that sums it here
// (surface_algorithm1_vpl_fragment.glsl), otherwise in compute after the pass.
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

#ifdef TALLOW_VPL_IN_FRAGMENT
vec3 surroundingsIrradiance(vec3 p, vec3 n) { return vplIrradiance(p, n); }
#else
// The VPLs' light is added after the pass, in compute, from the receivers' G-buffer this pass
// leaves (maps/vpl_receivers.comp).
vec3 surroundingsIrradiance(vec3 p, vec3 n) { return vec3(0.0); }
#endif
