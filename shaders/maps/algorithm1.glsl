// Step 3 of the paper: Algorithm 1, the scattered radiosity B at x_o from the K maps, each
// weighted by whether its camera sees x_o (a depth comparison with ε_bias, four bilinear taps
// around the point so that texels near a map's silhouette blend), after moving x_o by ε_comb
// toward −n_o in the part perpendicular to the map direction, and by cos^p θ (sss.view_weight;
// p = 0 is the paper's equal weighting). Each map's texels hold Σ_F (B_N, 1): dividing a look-up by
// its alpha gives the mean B over the frames and, at coarser mip levels, over the covered texels
// only, so a footprint that reaches past the object's silhouette is not darkened by the empty
// texels around it (at level 0 alpha is F, the paper's division by F).
uniform int uMapCount;                 // K
uniform float uEpsBias;                // ε_bias, world units
uniform float uEpsComb;                // ε_comb, world units
uniform float uViewWeight;             // p of the weight cos^p θ of a map seeing x_o at θ (0: the paper)
uniform sampler2DArray uMaps;          // Σ over frames of B_N, with mipmaps
// The widest footprint, in map texture units, that a look-up filters over: half the shortest
// diffusion length 1/σ_tr. B varies on that scale; a pixel wider than it (a large object far away)
// would otherwise average B over its whole footprint (more still on a map that sees x_o at a
// grazing angle), where the camera, like the reference, takes B at the pixel's centre (issue 17).
uniform float uMaxFootprint;
// For the camera's look-ups (uNarrowFootprint = 1; the VPLs keep their patches' footprint) the
// footprint, after that cap, is scaled by F^(-1/4), F the frames the texels at x_o hold (level 0's
// alpha; with sss.history each texel counts its own). The paper's mipmaps smooth a young map's noise,
// but they average B rather than sample it at x_o, which biases B where it is far from linear across
// the footprint: the backlit bunny's rim, where the thickness and so B change tenfold within a pixel,
// read 50% bright (issue 17). Narrowing the footprint as the frames accumulate keeps the noise falling
// (the texels averaged fall as F^(-1/2) while each texel's frames grow as F) and the bias going to 0
// (as F^(-1/2)); once under a texel the look-up is the bilinear tap at x_o (docs/radiosity-maps.md).
uniform int uNarrowFootprint;
uniform sampler2DArrayShadow uMapDepth;
struct MapViewGpu { mat4 toTexture; vec4 direction; vec4 depthScale; };  // depthScale.x: depth units per metre
layout(std430, binding = 5) readonly buffer MapViews { MapViewGpu mapViews[]; };

// sss.maps=auto counts which map first sees each point (maps/coverage_counts.glsl). The VPL pass
// counts here (uCountVplCoverage 1; 0: no counting this frame); the camera's pixels are counted
// after the camera pass from what surface.frag writes per pixel (maps/coverage_histogram.comp), so
// that hidden fragments, drawn before what hides them, do not count.
#include "maps/coverage_count_buffer.glsl"
uniform int uCountVplCoverage;

void countVplCoverage(int firstMap) {
  if (uCountVplCoverage != 0) countInto(COVERAGE_VPLS, firstMap);
}

// The level-0 texels of map k around the point at texture coordinates p (its bilinear 2×2) whose
// surface lies within a slack of x_o's depth (zNear, zFar: x_o's depth ∓ the slack), each by its
// bilinear weight: a bilinear look-up would average in the texels of a nearer surface that hides x_o
// from the map (the drip overhanging the puddle) or of a farther one beyond x_o's silhouette.
vec4 texelsSeeing(vec2 p, int k, float zNear, float zFar) {
  vec2 size = vec2(textureSize(uMaps, 0).xy);
  vec2 f = p * size - 0.5;
  vec2 w = fract(f);
  // The corner the 2×2 share, so that the gathers take the same texels as the weights.
  vec3 corner = vec3((floor(f) + 1.0) / size, float(k));
  // textureGather's order: (0, 1), (1, 1), (1, 0), (0, 0) of the 2×2.
  vec4 weight = vec4((1.0 - w.x) * w.y, w.x * w.y, w.x * (1.0 - w.y), (1.0 - w.x) * (1.0 - w.y)) *
                textureGather(uMapDepth, corner, zNear) * (1.0 - textureGather(uMapDepth, corner, zFar));
  return vec4(dot(weight, textureGather(uMaps, corner, 0)), dot(weight, textureGather(uMaps, corner, 1)),
              dot(weight, textureGather(uMaps, corner, 2)), dot(weight, textureGather(uMaps, corner, 3)));
}

// dpdx, dpdy: screen-space derivatives of x_o, taken by the caller in uniform control flow (they
// are undefined inside this loop once some fragments skip a map); the mip level then follows the
// pixel's footprint on each map. seenBy: Σ of the weights of the maps that see x_o; firstMap: the
// first of them, secondFacingMap: the second within COVERAGE_MIN_COS of n_o (−1: none).
vec3 scatteredRadiosity(vec3 xo, vec3 no, vec3 dpdx, vec3 dpdy, out float seenBy, out int firstMap,
                        out int secondFacingMap) {
  vec3 colour = vec3(0.0);
  float n = 0.0;
  firstMap = -1;
  secondFacingMap = -1;
  int facing = 0;  // maps so far that see x_o within COVERAGE_MIN_COS of n_o
  for (int k = 0; k < uMapCount; ++k) {
    vec3 d = mapViews[k].direction.xyz;
    float cosTheta = clamp(dot(no, d), 0.0, 1.0);
    vec3 x = xo - uEpsComb * (no - cosTheta * d);
    vec4 t = mapViews[k].toTexture * vec4(x, 1.0);
    vec2 dx = (mapViews[k].toTexture * vec4(dpdx, 0.0)).xy, dy = (mapViews[k].toTexture * vec4(dpdy, 0.0)).xy;
    float footprint = max(length(dx), length(dy));
    if (footprint > uMaxFootprint) {
      dx *= uMaxFootprint / footprint;
      dy *= uMaxFootprint / footprint;
    }
    float z = t.z - uEpsBias * mapViews[k].depthScale.x;
    vec2 texel = 0.5 / vec2(textureSize(uMapDepth, 0).xy);
    vec2 taps[4] = vec2[4](t.xy + vec2(-texel.x, -texel.y), t.xy + vec2(texel.x, -texel.y),
                           t.xy + vec2(-texel.x, texel.y), t.xy + vec2(texel.x, texel.y));
    float seen[4];
    for (int i = 0; i < 4; ++i) seen[i] = texture(uMapDepth, vec4(taps[i], float(k), z));
    float v = 0.25 * (seen[0] + seen[1] + seen[2] + seen[3]);
    bool edge = v < 1.0;  // some taps fall on a surface nearer the map than x_o
    // A map that sees x_o at θ from its normal spreads a texel over 1/cos θ of surface (and its
    // mipmaps blur further): weighting by cos^p θ lets the maps that see x_o face-on decide, while
    // the normalisation by n keeps every point that any map sees.
    if (uViewWeight > 0.0) v *= pow(max(cosTheta, 1e-4), uViewWeight);
    if (v <= 0.0) continue;
    if (uNarrowFootprint != 0) {
      float frames = textureLod(uMaps, vec3(t.xy, float(k)), 0.0).a;
      float narrow = frames > 1.0 ? pow(frames, -0.25) : 1.0;
      dx *= narrow;
      dy *= narrow;
    }
    // The filtered look-up reads about a footprint around x_o (its mip level's texels are aligned
    // blocks of the footprint's size): if a surface nearer the map lies within it (the candle's rim
    // beside the puddle it overhangs, seen from above), that surface's B would be averaged in, so
    // the footprint's corners are tested too and such a look-up is an edge as well.
    if (!edge && max(length(dx), length(dy)) > 2.0 * texel.x) {
      vec2 a = dx + dy, b = dx - dy;
      vec2 corners[4] = vec2[4](t.xy + a, t.xy - a, t.xy + b, t.xy - b);
      for (int i = 0; i < 4 && !edge; ++i) edge = texture(uMapDepth, vec4(corners[i], float(k), z)) < 1.0;
    }
    // Where x_o lies at the edge of what map k sees (a puddle beside the candle's foot, seen from
    // above past the candle's top), a filtered look-up would mix in the texels of the surface in
    // front, whose B can be many times x_o's: bright and dark single pixels along the edge (issue
    // 36: 5 dark dots on the default candle's puddle, 2 without the mix). There B is taken from the
    // level-0 texels of x_o's surface only, each tested on its own (texelsSeeing): the taps' bilinear
    // look-ups, weighted by their filtered depth tests, still averaged in the texels of the drip
    // overhanging the puddle (a red pixel 8.9x the reference's at t = 16 s, 160x90).
    vec4 m = vec4(0.0);
    if (edge) {
      // The slack: ε_bias, plus how far the depth of x_o's own surface changes over the 2 texels
      // the taps' 2×2s reach (depth spans 2 radii and a texel 2 radii / size, so tan θ / size a
      // texel). Without it a map that sees a flat surface at 60° (its depth changing by 1.7 texel
      // widths a texel, ε_bias under one at 128²) lost those texels and skipped x_o
      // (MapCountRenderer.TheSlabsPixelsAreBinnedByTheSecondHaltonDirectionWithin60DegreesOfUp).
      float tanTheta = sqrt(max(1.0 - cosTheta * cosTheta, 0.0)) / max(cosTheta, 0.05);
      float slack = uEpsBias * mapViews[k].depthScale.x + 2.0 * tanTheta / float(textureSize(uMapDepth, 0).x);
      for (int i = 0; i < 4; ++i) m += texelsSeeing(taps[i], k, t.z - slack, t.z + slack);
    } else {
      m = textureGrad(uMaps, vec3(t.xy, float(k)), dx, dy);
    }
    if (m.a <= 0.0) continue;
    if (firstMap < 0) firstMap = k;
    if (cosTheta >= COVERAGE_MIN_COS && ++facing == 2) secondFacingMap = k;
    colour += v * m.rgb / m.a;
    n += v;
  }
  seenBy = n;
  return n > 0.0 ? colour / n : vec3(0.0);
}
