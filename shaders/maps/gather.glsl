// The gather of step 2 (§3.2), shared by the fragment pass (radiosity_map.frag, the paper's) and
// the compute pass over the maps' G-buffer (radiosity_map.comp): scattered radiosity B at a map
// texel by the Monte Carlo estimator of Eq. 9, N samples shared by the three colour bands, drawn
// from the mixture of their σ_tr (Eqs. 11–12, sssDrawSharedSample), looked up in the light
// G-buffers; point lights with the stereographic correction (Eqs. 13–14). Both passes call this
// with the same inputs and seeds, so they agree.
#include "bssrdf/bssrdf.glsl"
#include "maps/estimator.glsl"
#include "maps/lights_gbuffer.glsl"
#include "materials/slots.glsl"

uniform vec3 uSigmaA[SSS_MAX_SLOTS];    // mm⁻¹ per band (η: uSlotEta)
uniform vec3 uSigmaS[SSS_MAX_SLOTS];
uniform vec3 uG[SSS_MAX_SLOTS];
uniform int uBssrdfModel;               // BSSRDF_MODEL_*
uniform int uSamples;                   // N
uniform int uFrame;                     // frame index of this accumulation (seeds)
uniform int uStereographic;             // 1: Eqs. 13–14 for point lights
uniform int uProjectedArea;             // 1: the sampling plane's area against the surface's (sss.projected_area)
uniform int uTexelPlane;                // 1: x_i on the G-buffer texel's tangent plane (sss.texel_plane)
uniform float uPointShare;              // point lights: the stereographic density's share (sss.point_share)

const float MM_PER_M = 1000.0;

// B_N at one map texel: x_o [m] with unit normal n_o on translucent slot `slot` (x_o's own: a
// candle's pool point has the liquid's slot, surfaceSlot), texel (x, y) of map `map` (the random
// streams), all lights, the three colour bands. Light enters anywhere on the same object (any of
// its slots) and leaves with x_o's material's BSSRDF. Each sample is drawn once for
// the three bands (sssDrawSharedSample, issue 17): one look-up, x_i, n_i and area ratio per sample,
// then the term of Eq. 9 per band with that band's coefficients and the shared weight.
vec3 gatherScatteredRadiosity(vec3 xoWorld, vec3 no, uvec2 texel, int map, int slot) {
  vec3 xo = xoWorld * MM_PER_M;
  BssrdfCoefficients k[3];
  vec3 sigmaTr;
  for (int c = 0; c < 3; ++c) {
    k[c] = bssrdfCoefficients(uSigmaA[slot][c], uSigmaS[slot][c], uG[slot][c], uSlotEta[slot]);
    sigmaTr[c] = sssSamplingSigmaTr(k[c]);
  }
  vec3 b = vec3(0.0);
  // Directional lights: samples on the light's view plane around x_o, looked up orthographically.
  for (int l = 0; l < uSssDirCount; ++l) {
    vec3 w = uSssDirDirection[l];
    vec3 acc = vec3(0.0);
    // x_o behind the lit surface (issue 17): the depth at which the light enters, from the G-buffer
    // at x_o's own place, scales a second density (sssBacklitRadius; share sss.point_share).
    // The extra look-up only when a share is given (and the area ratio, as for point lights).
    float backlit = 0.0;
    if (uProjectedArea != 0 && uPointShare > 0.0) {
      GSample front = directionalGBuffer(l, xoWorld);
      float depth = sameObjectTag(front.tag, slot) ? dot(front.position * MM_PER_M - xo, w) : 0.0;
      backlit = sssBacklitRadius(depth, min(sigmaTr.x, min(sigmaTr.y, sigmaTr.z)));
    }
    for (int j = 0; j < uSamples; ++j) {
      SssSample s = sssDrawSharedSample(xo, uSssDirTangent[l], uSssDirBitangent[l], sigmaTr, backlit,
                                        backlit > 0.0 ? uPointShare : 0.0, texel.x, texel.y, uint(map),
                                        uint(uFrame), uint(j), uint(uSamples));
      GSample g = directionalGBuffer(l, s.xj / MM_PER_M);
      if (!sameObjectTag(g.tag, slot)) continue;  // another object or an occluder: x_j is not lit here
      // x_i keeps x_j's exact place across the light's view (the texel's centre would quantise
      // r to the G-buffer grid, which biases B where x_o sits at a fixed offset in that grid: an
      // aligned camera, a flat slab) and lies on the texel's tangent plane (sssPointOnTexel).
      vec3 ni = normalize(g.normal);
      vec3 xi = sssPointOnTexel(s.xj, w, g.position * MM_PER_M, ni, uTexelPlane);
      // The samples are spread over the light's view plane, whose area element is cos θ_ℓ times
      // the surface's (dA_view = cos θ_ℓ dA): Eq. 7 over the view plane is Eq. 9 divided by
      // cos θ_ℓ. The paper's Eq. 9 keeps the cosine (uProjectedArea = 0), which darkens surfaces
      // lit at grazing angles by a further cos θ_ℓ (its §4, Fig. 8: "light missing").
      float weight = uProjectedArea != 0 ? s.weight / max(dot(ni, w), 1e-3) : s.weight;
      for (int c = 0; c < 3; ++c) acc[c] += sssRadiosityTerm(uBssrdfModel, xi, ni, w, xo, no, k[c], weight);
    }
    for (int c = 0; c < 3; ++c) b[c] += sssRadiosityFromSum(acc[c], uSssDirIrradiance[l][c], uSamples);
  }
  // Point lights: samples on x_o's tangent plane, looked up in the cube G-buffer by direction.
  vec3 t1 = normalize(abs(no.x) < 0.9 ? cross(no, vec3(1, 0, 0)) : cross(no, vec3(0, 1, 0)));
  vec3 t2 = cross(no, t1);
  for (int l = 0; l < uSssPointCount; ++l) {
    vec3 xl = uSssPointPosition[l] * MM_PER_M;
    vec3 acc = vec3(0.0);
    for (int j = 0; j < uSamples; ++j) {
      // Eq. 12 mixed with the stereographic density about the light (sss.point_share, issue 17);
      // Eq. 12 alone for the paper's Eq. 9 (no area ratio), whose integrand over the plane grows
      // with r where the stereographic look-up crowds far samples onto the sphere.
      SssSample s = sssDrawSharedSample(xo, t1, t2, sigmaTr, length(xl - xo), uProjectedArea != 0 ? uPointShare : 0.0,
                                        texel.x, texel.y, uint(map), uint(uFrame), uint(j), uint(uSamples));
      vec3 dir = uStereographic != 0 ? sssStereographicLookupDirection(xo, s.xj, xl) : sssPlanarLookupDirection(s.xj, xl);
      GSample g = pointGBuffer(l, dir);
      if (!sameObjectTag(g.tag, slot)) continue;
      // Along the exact look-up direction (as above: no quantisation of the direction to the
      // cube's texels), on the texel's tangent plane.
      vec3 ni = normalize(g.normal);
      vec3 xi = sssPointOnTexel(xl, normalize(dir), g.position * MM_PER_M, ni, uTexelPlane);
      vec3 toLight = xl - xi;
      float d2 = dot(toLight, toLight) / (MM_PER_M * MM_PER_M);  // m²: E = I / d²
      // E = I/d² at x_i varies per sample, so it enters the sum (Eq. 9 with L_ℓ inside).
      float weight = s.weight / max(d2, 1e-12);
      // The samples' density is on x_o's tangent plane; Eq. 7 integrates over the surface.
      if (uProjectedArea != 0)
        weight *= uStereographic != 0 ? sssStereographicAreaRatio(xo, no, s.xj, xl, xi, ni)
                                      : sssPlanarAreaRatio(no, s.xj, xl, xi, ni);
      vec3 wl = normalize(toLight);
      for (int c = 0; c < 3; ++c) acc[c] += sssRadiosityTerm(uBssrdfModel, xi, ni, wl, xo, no, k[c], weight);
    }
    for (int c = 0; c < 3; ++c) b[c] += sssRadiosityFromSum(acc[c], uSssPointIntensity[l][c], uSamples);
  }
  return b;
}
