#version 450 core
// render.local_exposure: local adaptation of the picture shown (sss/local_exposure.h). The picture's
// log luminance is split into a base layer — its edge-aware local mean — and detail (Durand and
// Dorsey 2002, "Fast bilateral filtering for the display of high-dynamic-range images", §5: the
// base is the bilateral filter of log luminance, σ_s 2% of the picture, σ_r 0.4 decades); each
// region's base below mid grey is brought a share s nearer to it, detail untouched. The bilateral
// filter is computed on a bilateral grid (Chen, Paris and Durand 2007, "Real-time edge-aware image
// processing with the bilateral grid", §3-4): splat into cells of S × S pixels × one range bin,
// blur the homogeneous values (sum, count) in space and range, slice by trilinear interpolation at
// each pixel's position and log luminance, divide. Five steps:
//  uStep 0: one invocation per grid column (gx, gy): its S × S pixels splatted linearly into the
//           two nearest range bins of uGridOut (rg: Σ w·log₂Y, Σ w);
//  uStep 1-3: the grid blurred by [1 4 6 4 1]/16 along x, y, then range (uGrid → uGridOut; zero
//           outside the grid, so cells at the border keep their own normalisation);
//  uStep 4: the slice: base b at the pixel; its gain 2^(s · max(0, log₂ g − b)) into uGainOut;
//  uStep 5: the picture times each pixel's gain, made consistent with its neighbours' (below) into
//           uOutput.
// Step 5: a pixel on an anti-aliased edge is a blend, Y = α Y_hi + (1 − α) Y_lo, of the two sides
// around it. Sliced at its own, in-between luminance, its base is neither side's (the grid's bins
// there hold little but the bright side, blurred across range), so it was lifted less than the dark
// side and more than the bright one: the wax's silhouette against the lifted table showed as a dark
// outline, darker than both (issue 36: the rim's dotted outline). The picture shown should be the
// same blend of what each side shows, α Y_hi g_hi + (1 − α) Y_lo g_lo: with Y_lo, Y_hi the darkest
// and brightest of the 3 × 3 pixels around it (the still's box filter blends a pixel only with what
// its own square holds, so the pure sides are its neighbours) and g their gains, α from Y. A pixel
// that is the darkest or brightest of its 3 × 3 keeps its own gain (uniform regions, detail,
// a sharp edge's two sides).
#include "common/coverage_masks.glsl"
layout(local_size_x = 8, local_size_y = 8) in;

layout(rg32f, binding = 0) uniform writeonly image3D uGridOut;   // steps 0-3
layout(rgba32f, binding = 1) uniform writeonly image2D uOutput;  // step 5: the picture shown
layout(r32f, binding = 2) uniform writeonly image2D uGainOut;    // step 4: each pixel's gain
uniform sampler2D uPicture;  // the picture, linear (steps 0, 4 and 5)
uniform sampler3D uGrid;     // steps 1-4: the grid (step 4: the blurred grid, filtered linearly)
uniform sampler2D uGain;     // step 5: the gains of step 4
uniform int uStep;
uniform int uCell;            // S, pixels per grid cell along x and y
uniform float uExposureScale; // e = 2^render.exposure_ev: luminance as the tone map sees it
uniform float uStrength;      // s = render.local_exposure
uniform sampler2D uCoverage;  // step 5: the camera's coverage, whose code becomes the output's alpha
uniform int uCoverageAlpha;   // 0: the output keeps the picture's alpha (no coverage bound)

const int kBins = 22;             // range bins of the grid
const float kBinStops = 4.0 / 3.0;  // σ_r: 0.4 decades = 1.33 stops per bin (Durand and Dorsey §5.2)
const float kLowStops = -24.0;    // log₂ of the darkest luminance told apart (black is put there)
const float kGreyStops = -2.4739312;  // log₂ 0.18: scene mid grey, where the lift ends

float luminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

// log₂ of the exposed luminance, and its place along the grid's range axis (in bins).
float logLuminance(vec3 c) {
  float y = luminance(c) * uExposureScale;
  return y > 0.0 ? max(log2(y), kLowStops) : kLowStops;
}
float rangeCoordinate(float stops) { return clamp((stops - kLowStops) / kBinStops, 0.0, float(kBins - 1)); }

void splat() {
  ivec3 cell = ivec3(gl_GlobalInvocationID.xy, 0);
  ivec3 gridSize = imageSize(uGridOut);
  if (any(greaterThanEqual(cell.xy, gridSize.xy))) return;
  ivec2 size = textureSize(uPicture, 0);
  vec2 bins[kBins];
  for (int b = 0; b < kBins; ++b) bins[b] = vec2(0.0);
  for (int j = 0; j < uCell; ++j)
    for (int i = 0; i < uCell; ++i) {
      ivec2 p = cell.xy * uCell + ivec2(i, j);
      if (any(greaterThanEqual(p, size))) continue;
      float stops = logLuminance(texelFetch(uPicture, p, 0).rgb);
      float z = rangeCoordinate(stops);
      int b0 = min(int(z), kBins - 2);
      float f = z - float(b0);
      bins[b0] += (1.0 - f) * vec2(stops, 1.0);
      bins[b0 + 1] += f * vec2(stops, 1.0);
    }
  for (int b = 0; b < kBins; ++b) imageStore(uGridOut, ivec3(cell.xy, b), vec4(bins[b], 0.0, 0.0));
}

void blur(ivec3 axis) {
  ivec3 c = ivec3(gl_GlobalInvocationID.xy, 0);
  ivec3 gridSize = textureSize(uGrid, 0);
  if (any(greaterThanEqual(c.xy, gridSize.xy))) return;
  const float weights[5] = float[](1.0, 4.0, 6.0, 4.0, 1.0);
  for (c.z = 0; c.z < gridSize.z; ++c.z) {
    vec2 sum = vec2(0.0);
    for (int k = -2; k <= 2; ++k) {
      ivec3 q = c + k * axis;
      if (any(lessThan(q, ivec3(0))) || any(greaterThanEqual(q, gridSize))) continue;
      sum += weights[k + 2] * texelFetch(uGrid, q, 0).rg;
    }
    imageStore(uGridOut, c, vec4(sum / 16.0, 0.0, 0.0));
  }
}

void slice() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = textureSize(uPicture, 0);
  if (any(greaterThanEqual(p, size))) return;
  vec4 picture = texelFetch(uPicture, p, 0);
  float stops = logLuminance(picture.rgb);
  ivec3 gridSize = textureSize(uGrid, 0);
  // Cell (gx, gy)'s centre is at pixel (g + ½) S; range bin b's at b bins.
  vec3 at = vec3((vec2(p) + 0.5) / float(uCell) / vec2(gridSize.xy), (rangeCoordinate(stops) + 0.5) / float(gridSize.z));
  vec2 g = texture(uGrid, at).rg;
  float base = g.y > 1e-6 ? g.x / g.y : stops;
  float lift = uStrength * max(0.0, kGreyStops - base);
  imageStore(uGainOut, p, vec4(exp2(lift), 0.0, 0.0, 0.0));
}

void blendConsistently() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = textureSize(uPicture, 0);
  if (any(greaterThanEqual(p, size))) return;
  vec4 picture = texelFetch(uPicture, p, 0);
  float y = luminance(picture.rgb), gain = texelFetch(uGain, p, 0).r;
  float lo = y, hi = y, gainLo = gain, gainHi = gain;
  for (int j = -1; j <= 1; ++j)
    for (int i = -1; i <= 1; ++i) {
      ivec2 q = clamp(p + ivec2(i, j), ivec2(0), size - 1);
      float yq = luminance(texelFetch(uPicture, q, 0).rgb);
      if (yq < lo) lo = yq, gainLo = texelFetch(uGain, q, 0).r;
      if (yq > hi) hi = yq, gainHi = texelFetch(uGain, q, 0).r;
    }
  if (y > lo && y < hi) {
    float alpha = (y - lo) / (hi - lo);
    gain = (alpha * hi * gainHi + (1.0 - alpha) * lo * gainLo) / y;
  }
  float a = uCoverageAlpha != 0 ? coverageCode(texelFetch(uCoverage, p, 0)) : picture.a;
  imageStore(uOutput, p, vec4(picture.rgb * gain, a));
}

void main() {
  if (uStep == 0) splat();
  else if (uStep == 1) blur(ivec3(1, 0, 0));
  else if (uStep == 2) blur(ivec3(0, 1, 0));
  else if (uStep == 3) blur(ivec3(0, 0, 1));
  else if (uStep == 4) slice();
  else blendConsistently();
}
