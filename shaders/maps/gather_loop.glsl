// The gather of step 2 (§3.2): scattered radiosity B at x_o by the Monte Carlo estimator of Eq. 9,
// over every light and N samples, written once and compiled as GLSL (maps/gather.glsl: the map
// passes and the no-cache camera pass) and as C++ in float, double and the FLOP-counting scalar
// (sss/maps/radiosity_estimator.cpp, app/bench_report/gather_flops.cpp). Conventions:
// shaders/bssrdf/real.glsl; the per-sample pieces are maps/estimator.glsl's. Units: mm, mm⁻¹.
//
// What differs between the sides is where the lights and their G-buffers come from. The including
// side declares, before this file, the type SssGatherScene with the members directionalCount and
// pointCount, and defines, after it, the four accessors declared below: a light's parameters, and
// its G-buffer's texel over a point (directional: orthographic, by position) or along a direction
// (point light: the cube, by direction from the light). A texel that does not see a surface of the
// object of `slot` (another object, an occluder, nothing) reports found = 0.
#ifdef TALLOW_GLSL
#include "maps/estimator.glsl"
#endif

const real SSS_MM_PER_M = 1000.0;

// The gather's settings (sss.*); `spread` asks for the terms' variance too (the C++ standard
// error); the GPU passes 0 and the compiler drops that arithmetic.
struct SssGatherSettings {
  int model;          // BSSRDF_MODEL_*
  int samples;        // N
  uint frame;         // the accumulated frame F (seeds)
  int stereographic;  // 1: point lights looked up by Eqs. 13–14
  int projectedArea;  // 1: the sampling plane's area against the surface's (sss.projected_area)
  int texelPlane;     // 1: x_i on the G-buffer texel's tangent plane (sss.texel_plane)
  real pointShare;    // the second distance density's share (sss.point_share)
  int spread;         // 1: SssGatherSums.variance is computed
};

// A directional light: unit direction toward it, the orthonormal basis of its view plane (the
// samples' plane) and E on a surface facing it [W/m²].
struct SssDirectionalLight {
  real3 toLight;
  real3 t1;
  real3 t2;
  real3 irradiance;
};

// A point light: position [mm] and intensity [W/sr].
struct SssPointLight {
  real3 position;
  real3 intensity;
};

// What a light G-buffer texel saw: the surface point [mm] and its normal (not necessarily unit).
struct SssLightTexel {
  int found;
  real3 position;
  real3 normal;
};

// B per band [W/m²] and, with settings.spread, the variance of that estimate per band (the lights'
// estimates added as if independent: exact for one light).
struct SssGatherSums {
  real3 b;
  real3 variance;
};

TALLOW_FN SssDirectionalLight sssDirectionalLight(SssGatherScene scene, int light);
TALLOW_FN SssPointLight sssPointLight(SssGatherScene scene, int light);
TALLOW_FN SssLightTexel sssDirectionalTexel(SssGatherScene scene, int light, real3 pointMm, int slot);
TALLOW_FN SssLightTexel sssPointTexel(SssGatherScene scene, int light, real3 direction, int slot);

// The three bands' terms of Eq. 9 for one sample (shared x_i, n_i and weight, issue 17).
TALLOW_FN real3 sssBandTerms(int model, real3 xi, real3 ni, real3 wl, real3 xo, real3 no, BssrdfCoefficients k0,
                             BssrdfCoefficients k1, BssrdfCoefficients k2, real weight) {
  return real3(sssRadiosityTerm(model, xi, ni, wl, xo, no, k0, weight),
               sssRadiosityTerm(model, xi, ni, wl, xo, no, k1, weight),
               sssRadiosityTerm(model, xi, ni, wl, xo, no, k2, weight));
}

// One light's B from its terms' sum (Eq. 9: π L_ℓ/N Σ), and its variance from their squares.
TALLOW_FN SssGatherSums sssLightSums(real3 sum, real3 squares, real3 radiance, SssGatherSettings set) {
  SssGatherSums sums;
  sums.b = real3(sssRadiosityFromSum(sum.x, radiance.x, set.samples),
                sssRadiosityFromSum(sum.y, radiance.y, set.samples),
                sssRadiosityFromSum(sum.z, radiance.z, set.samples));
  sums.variance = real3(0);
  if (set.spread != 0 && set.samples > 1) {
    real n = real(set.samples);
    real3 scale = real(BSSRDF_PI) * radiance;
    real3 sampleVariance = max((squares - sum * sum / n) / (n - real(1)), real3(0));
    sums.variance = scale * scale * sampleVariance / n;
  }
  return sums;
}

// A directional light: samples on its view plane around x_o, looked up orthographically.
TALLOW_FN SssGatherSums sssGatherDirectional(SssGatherScene scene, SssGatherSettings set, int light, real3 xo,
                                             real3 no, BssrdfCoefficients k0, BssrdfCoefficients k1,
                                             BssrdfCoefficients k2, real3 sigmaTr, uint texelX, uint texelY, uint map,
                                             int slot) {
  SssDirectionalLight l = sssDirectionalLight(scene, light);
  real3 w = l.toLight;
  // x_o behind the lit surface (issue 17): the depth at which the light enters, from the G-buffer
  // at x_o's own place, scales a second density (sssBacklitRadius; share sss.point_share).
  // The extra look-up only when a share is given (and the area ratio, as for point lights).
  real backlit = real(0);
  if (set.projectedArea != 0 && set.pointShare > real(0)) {
    SssLightTexel front = sssDirectionalTexel(scene, light, xo, slot);
    real depth = front.found != 0 ? dot(front.position - xo, w) : real(0);
    backlit = sssBacklitRadius(depth, min(sigmaTr.x, min(sigmaTr.y, sigmaTr.z)));
  }
  real share = backlit > real(0) ? set.pointShare : real(0);
  real3 sum = real3(0);
  real3 squares = real3(0);
  for (int j = 0; j < set.samples; ++j) {
    SssSample s = sssDrawSharedSample(xo, l.t1, l.t2, sigmaTr, backlit, share, texelX, texelY, map, set.frame, uint(j),
                                      uint(set.samples));
    SssLightTexel g = sssDirectionalTexel(scene, light, s.xj, slot);
    if (g.found == 0) continue;  // another object or an occluder: x_j is not lit here
    // x_i keeps x_j's exact place across the light's view (the texel's centre would quantise r to
    // the G-buffer grid, which biases B where x_o sits at a fixed offset in that grid: an aligned
    // camera, a flat slab) and lies on the texel's tangent plane (sssPointOnTexel).
    real3 ni = normalize(g.normal);
    real3 xi = sssPointOnTexel(s.xj, w, g.position, ni, set.texelPlane);
    // The samples are spread over the light's view plane, whose area element is cos θ_ℓ times the
    // surface's (dA_view = cos θ_ℓ dA): Eq. 7 over the view plane is Eq. 9 divided by cos θ_ℓ.
    // The paper's Eq. 9 keeps the cosine (projectedArea = 0), which darkens surfaces lit at grazing
    // angles by a further cos θ_ℓ (its §4, Fig. 8: "light missing").
    real weight = set.projectedArea != 0 ? s.weight / max(dot(ni, w), real(1e-3)) : s.weight;
    real3 t = sssBandTerms(set.model, xi, ni, w, xo, no, k0, k1, k2, weight);
    sum = sum + t;
    if (set.spread != 0) squares = squares + t * t;
  }
  return sssLightSums(sum, squares, l.irradiance, set);
}

// A point light: samples on x_o's tangent plane (t1, t2), looked up in the cube G-buffer by
// direction (Eqs. 13–14 with settings.stereographic).
TALLOW_FN SssGatherSums sssGatherPoint(SssGatherScene scene, SssGatherSettings set, int light, real3 xo, real3 no,
                                       real3 t1, real3 t2, BssrdfCoefficients k0, BssrdfCoefficients k1,
                                       BssrdfCoefficients k2, real3 sigmaTr, uint texelX, uint texelY, uint map,
                                       int slot) {
  SssPointLight l = sssPointLight(scene, light);
  real3 xl = l.position;
  // Eq. 12 mixed with the stereographic density about the light (sss.point_share, issue 17); Eq. 12
  // alone for the paper's Eq. 9 (no area ratio), whose integrand over the plane grows with r where
  // the stereographic look-up crowds far samples onto the sphere.
  real share = set.projectedArea != 0 ? set.pointShare : real(0);
  real radius = length(xl - xo);
  real3 sum = real3(0);
  real3 squares = real3(0);
  for (int j = 0; j < set.samples; ++j) {
    SssSample s = sssDrawSharedSample(xo, t1, t2, sigmaTr, radius, share, texelX, texelY, map, set.frame, uint(j),
                                      uint(set.samples));
    real3 dir = set.stereographic != 0 ? sssStereographicLookupDirection(xo, s.xj, xl)
                                       : sssPlanarLookupDirection(s.xj, xl);
    SssLightTexel g = sssPointTexel(scene, light, dir, slot);
    if (g.found == 0) continue;
    // Along the exact look-up direction (no quantisation of the direction to the cube's texels), on
    // the texel's tangent plane.
    real3 ni = normalize(g.normal);
    real3 xi = sssPointOnTexel(xl, normalize(dir), g.position, ni, set.texelPlane);
    real3 toLight = xl - xi;
    real d2 = dot(toLight, toLight) / (SSS_MM_PER_M * SSS_MM_PER_M);  // m²: E = I / d²
    // E = I/d² at x_i varies per sample, so it enters the sum (Eq. 9 with L_ℓ inside).
    real weight = s.weight / max(d2, real(1e-12));
    // The samples' density is on x_o's tangent plane; Eq. 7 integrates over the surface.
    if (set.projectedArea != 0)
      weight = weight * (set.stereographic != 0 ? sssStereographicAreaRatio(xo, no, s.xj, xl, xi, ni)
                                                : sssPlanarAreaRatio(no, s.xj, xl, xi, ni));
    real3 t = sssBandTerms(set.model, xi, ni, normalize(toLight), xo, no, k0, k1, k2, weight);
    sum = sum + t;
    if (set.spread != 0) squares = squares + t * t;
  }
  return sssLightSums(sum, squares, l.intensity, set);
}

// B_N at x_o [mm] with unit normal n_o, emerging through the material (σ_a, σ_s, g per band
// [mm⁻¹], η) of translucent slot `slot` (x_o's own: a candle's pool point has the liquid's), for
// texel (x, y) of map `map` (the random streams), from every light of the scene. Light enters
// anywhere on the same object and leaves with x_o's material's BSSRDF. Each sample is drawn once
// for the three bands (sssDrawSharedSample, issue 17): one look-up, x_i, n_i and area ratio per
// sample, then the term of Eq. 9 per band with that band's coefficients and the shared weight.
TALLOW_FN SssGatherSums sssGatherScatteredRadiosity(SssGatherScene scene, SssGatherSettings set, real3 sigmaA,
                                                    real3 sigmaS, real3 g, real eta, real3 xo, real3 no, uint texelX,
                                                    uint texelY, uint map, int slot) {
  BssrdfCoefficients k0 = bssrdfCoefficients(sigmaA.x, sigmaS.x, g.x, eta);
  BssrdfCoefficients k1 = bssrdfCoefficients(sigmaA.y, sigmaS.y, g.y, eta);
  BssrdfCoefficients k2 = bssrdfCoefficients(sigmaA.z, sigmaS.z, g.z, eta);
  real3 sigmaTr = real3(sssSamplingSigmaTr(k0), sssSamplingSigmaTr(k1), sssSamplingSigmaTr(k2));
  SssGatherSums total;
  total.b = real3(0);
  total.variance = real3(0);
  for (int l = 0; l < scene.directionalCount; ++l) {
    SssGatherSums one = sssGatherDirectional(scene, set, l, xo, no, k0, k1, k2, sigmaTr, texelX, texelY, map, slot);
    total.b = total.b + one.b;
    total.variance = total.variance + one.variance;
  }
  // Point lights sample x_o's tangent plane.
  real3 t1 = normalize(abs(no.x) < real(0.9) ? cross(no, real3(1, 0, 0)) : cross(no, real3(0, 1, 0)));
  real3 t2 = cross(no, t1);
  for (int l = 0; l < scene.pointCount; ++l) {
    SssGatherSums one = sssGatherPoint(scene, set, l, xo, no, t1, t2, k0, k1, k2, sigmaTr, texelX, texelY, map, slot);
    total.b = total.b + one.b;
    total.variance = total.variance + one.variance;
  }
  return total;
}
