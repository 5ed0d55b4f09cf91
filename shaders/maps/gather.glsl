// The gather of step 2 (§3.2) on the GPU, shared by the fragment pass (radiosity_map.frag, the
// paper's), the compute pass over the maps' G-buffer (radiosity_map.comp) and the no-cache camera
// pass: the loops of maps/gather_loop.glsl (which the C++ estimator and the FLOP counter compile
// too) fed with this frame's uniforms and light G-buffers. The passes call it with the same inputs
// and seeds, so they agree.
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

// The lights as gather_loop.glsl sees them: the uniforms of lights_gbuffer.glsl.
struct SssGatherScene {
  int directionalCount;
  int pointCount;
};
#include "maps/gather_loop.glsl"

SssDirectionalLight sssDirectionalLight(SssGatherScene scene, int light) {
  SssDirectionalLight l;
  l.toLight = uSssDirDirection[light];
  l.t1 = uSssDirTangent[light];
  l.t2 = uSssDirBitangent[light];
  l.irradiance = uSssDirIrradiance[light];
  return l;
}

SssPointLight sssPointLight(SssGatherScene scene, int light) {
  SssPointLight l;
  l.position = uSssPointPosition[light] * MM_PER_M;
  l.intensity = uSssPointIntensity[light];
  return l;
}

SssLightTexel lightTexel(GSample g, int slot) {
  SssLightTexel t;
  t.found = sameObjectTag(g.tag, slot) ? 1 : 0;
  t.position = g.position * MM_PER_M;
  t.normal = g.normal;
  return t;
}

SssLightTexel sssDirectionalTexel(SssGatherScene scene, int light, vec3 pointMm, int slot) {
  return lightTexel(directionalGBuffer(light, pointMm / MM_PER_M), slot);
}

SssLightTexel sssPointTexel(SssGatherScene scene, int light, vec3 direction, int slot) {
  return lightTexel(pointGBuffer(light, direction), slot);
}

// B_N at one map texel: x_o [m] with unit normal n_o on translucent slot `slot` (x_o's own: a
// candle's pool point has the liquid's slot, surfaceSlot), texel (x, y) of map `map` (the random
// streams), all lights, the three colour bands (gather_loop.glsl).
vec3 gatherScatteredRadiosity(vec3 xoWorld, vec3 no, uvec2 texel, int map, int slot) {
  SssGatherScene scene;
  scene.directionalCount = uSssDirCount;
  scene.pointCount = uSssPointCount;
  SssGatherSettings set;
  set.model = uBssrdfModel;
  set.samples = uSamples;
  set.frame = uint(uFrame);
  set.stereographic = uStereographic;
  set.projectedArea = uProjectedArea;
  set.texelPlane = uTexelPlane;
  set.pointShare = uPointShare;
  set.spread = 0;
  return sssGatherScatteredRadiosity(scene, set, uSigmaA[slot], uSigmaS[slot], uG[slot], uSlotEta[slot],
                                     xoWorld * MM_PER_M, no, texel.x, texel.y, uint(map), slot).b;
}
