// The engines' diffusion profile's part of the camera pass (camera/surface_method.glsl): the
// radiosity burley.scatter computed at this pixel (sss/peers/burley.h); no light to the surroundings.
#include "camera/surface_method.glsl"

uniform sampler2D uBurleyRadiosity;

TranslucentShading translucentShading(vec3 xo, vec3 facing, vec3 dpdx, vec3 dpdy, int slot) {
  return shadingOf(texelFetch(uBurleyRadiosity, ivec2(gl_FragCoord.xy), 0).rgb);
}

vec3 surroundingsIrradiance(vec3 p, vec3 n) { return vec3(0.0); }
