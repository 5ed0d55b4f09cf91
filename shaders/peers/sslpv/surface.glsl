// SSLPV's part of the camera pass (camera/surface_method.glsl): B = π L_i of its Eq. 7 from the
// accumulation grid (peers/sslpv/lookup.glsl, Eqs. 6–7).
#include "camera/surface_method.glsl"
#include "peers/sslpv/lookup.glsl"

TranslucentShading translucentShading(vec3 xo, vec3 facing, vec3 dpdx, vec3 dpdy, int slot) {
  TranslucentShading s = shadingOf(vec3(0.0));
  s.b = sslpvRadiosity(xo, facing, s.seenBy);
  return s;
}

vec3 surroundingsIrradiance(vec3 p, vec3 n) { return vec3(0.0); }
