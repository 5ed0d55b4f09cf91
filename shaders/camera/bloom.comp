#version 450 core
// render.bloom: glare around light brighter than the display's white (the flame) as an
// energy-conserving point-spread function applied to the HDR picture before tone mapping
// (sss/bloom.h). Two steps:
//  uStep 0: the bright part B = L · max(0, 1 − 1 / (e Y)) of each pixel (e the exposure scale, Y the
//           luminance: the light above white at the picture's exposure, with the pixel's colour)
//           into level 0 of uBrightOut, whose box-filtered mip chain the host then builds;
//  uStep 1: level i of that chain is B blurred over 2^i pixels; the glare is the mean of levels 1 …
//           uLevels read with a cubic B-spline (bsplineLevel): equal energy in every octave of
//           radius, the 1/r² fall-off of the eye's glare PSF (Spencer, Shirley, Zimmerman and
//           Greenberg 1995, §3) cut at 2^uLevels pixels. Each level keeps B's mean, so
//           L' = L + s (glare − B) keeps the total flux: a share s of the bright light is spread,
//           not added, and light below white is untouched.
#include "common/coverage_masks.glsl"
layout(local_size_x = 16, local_size_y = 16) in;

layout(rgba32f, binding = 0) uniform writeonly image2D uOutput;     // step 1: the picture shown
layout(rgba32f, binding = 1) uniform writeonly image2D uBrightOut;  // step 0: level 0 of the chain
uniform sampler2D uRadiance;  // the picture, linear
uniform sampler2D uBright;    // step 1: the bright part's mip chain
uniform int uStep;
uniform int uLevels;          // glare levels, 1 … uLevels
uniform float uShare;         // s
uniform float uExposureScale; // e = 2^render.exposure_ev
uniform sampler2D uCoverage;  // the camera's coverage: its code becomes the output's alpha
uniform int uCoverageAlpha;   // 0: the output keeps the picture's alpha (no coverage bound)

vec3 brightPart(vec3 c) {
  float y = dot(c, vec3(0.2126, 0.7152, 0.0722)) * uExposureScale;
  return y > 1.0 ? c * (1.0 - 1.0 / y) : vec3(0.0);
}

// Level `lod` of the chain reconstructed with the cubic B-spline (four bilinear taps, Sigg and
// Hadwiger 2005): read bilinearly, the coarse levels' texels show as squares in the glare's faint
// tail, which render.local_exposure lifts into view; the B-spline's weights sum to 1 and are
// smooth, so each level keeps B's mean and its tail is round to the eye (issue 36).
vec3 bsplineLevel(vec2 uv, int lod) {
  vec2 size = vec2(textureSize(uBright, lod));
  vec2 st = uv * size - 0.5, i = floor(st), f = st - i;
  vec2 w0 = (1.0 - f) * (1.0 - f) * (1.0 - f) / 6.0;
  vec2 w1 = (4.0 - 6.0 * f * f + 3.0 * f * f * f) / 6.0;
  vec2 w3 = f * f * f / 6.0;
  vec2 w2 = 1.0 - w0 - w1 - w3;
  vec2 g0 = w0 + w1, g1 = w2 + w3;
  vec2 h0 = (i - 0.5 + w1 / g0) / size, h1 = (i + 1.5 + w3 / g1) / size;  // tap centres, texture units
  float l = float(lod);
  return g0.y * (g0.x * textureLod(uBright, vec2(h0.x, h0.y), l).rgb + g1.x * textureLod(uBright, vec2(h1.x, h0.y), l).rgb) +
         g1.y * (g0.x * textureLod(uBright, vec2(h0.x, h1.y), l).rgb + g1.x * textureLod(uBright, vec2(h1.x, h1.y), l).rgb);
}

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = textureSize(uRadiance, 0);
  if (any(greaterThanEqual(p, size))) return;
  vec4 picture = texelFetch(uRadiance, p, 0);
  if (uStep == 0) {
    imageStore(uBrightOut, p, vec4(brightPart(picture.rgb), 1.0));
    return;
  }
  vec2 uv = (vec2(p) + 0.5) / vec2(size);
  vec3 glare = vec3(0.0);
  for (int i = 1; i <= uLevels; ++i) glare += bsplineLevel(uv, i);
  glare /= float(max(uLevels, 1));
  vec3 bright = texelFetch(uBright, p, 0).rgb;
  float alpha = uCoverageAlpha != 0 ? coverageCode(texelFetch(uCoverage, p, 0)) : picture.a;
  imageStore(uOutput, p, vec4(picture.rgb + uShare * (glare - bright), alpha));
}
