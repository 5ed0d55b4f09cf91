// The albedo baseline's part of the camera pass (camera/surface_method.glsl): no transport, so no
// translucent shading (translucent objects are drawn as opaque ones) and nothing carried around.
#include "camera/surface_method.glsl"

TranslucentShading translucentShading(vec3 xo, vec3 facing, vec3 dpdx, vec3 dpdy, int slot) {
  return shadingOf(vec3(0.0));
}

vec3 surroundingsIrradiance(vec3 p, vec3 n) { return vec3(0.0); }
