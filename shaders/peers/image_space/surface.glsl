// The image-space method's part of the camera pass (camera/surface_method.glsl): the accumulation
// at this pixel (peers/image_space/result.glsl).
#include "camera/surface_method.glsl"
#include "peers/image_space/result.glsl"

TranslucentShading translucentShading(vec3 xo, vec3 facing, vec3 dpdx, vec3 dpdy, int slot) {
  return shadingOf(imageSpaceRadiosity(ivec2(gl_FragCoord.xy)));
}

vec3 surroundingsIrradiance(vec3 p, vec3 n) { return vec3(0.0); }
