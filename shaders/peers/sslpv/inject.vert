#version 450 core
// SSLPV injection (sss/peers/sslpv_injection.h; the paper's §3.1): vertex gl_VertexID is one texel of the
// light G-buffers, directional layers first (uMapSize² texels each), then the six faces of each
// point light's cube. A texel that sees a translucent object becomes the VPL of Eq. 1,
// I_p(ω) = (1/π) T Φ_p max(0, ω_t·ω), in the cell half a cell inside the surface from x_p.
#include "maps/lights_gbuffer.glsl"
#include "bssrdf/fresnel.glsl"
#include "peers/sslpv/sh.glsl"
#include "materials/slots.glsl"  // uSlotEta: η of each translucent slot (RadiosityMaps::setGatherUniforms)
uniform int uMapSize;               // texels per side of each G-buffer layer or cube face
uniform vec3 uGridOrigin;           // m
uniform float uGridCell;            // m
uniform int uGridSize;

flat out ivec3 vCell;  // x < 0: nothing to inject
flat out vec4 vR, vG, vB;

// The direction from a cube's centre through texel (x, y) of `face` (GL's face order and
// orientation, OpenGL 4.5 §8.13: the inverse of the (s, t) of each major axis).
vec3 cubeTexelDirection(int face, int x, int y) {
  float a = 2.0 * (float(x) + 0.5) / float(uMapSize) - 1.0;
  float b = 2.0 * (float(y) + 0.5) / float(uMapSize) - 1.0;
  if (face == 0) return vec3(1.0, -b, -a);
  if (face == 1) return vec3(-1.0, -b, a);
  if (face == 2) return vec3(a, 1.0, b);
  if (face == 3) return vec3(a, -1.0, -b);
  if (face == 4) return vec3(a, -b, 1.0);
  return vec3(-a, -b, -1.0);
}

void main() {
  vCell = ivec3(-1);
  vR = vG = vB = vec4(0.0);
  gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
  int perLayer = uMapSize * uMapSize;
  int index = gl_VertexID;
  GSample s;
  vec3 toLight;  // unit, from x_p toward the light
  vec3 flux;     // Φ_p per band [W] through the texel
  if (index < uSssDirCount * perLayer) {
    int light = index / perLayer, texel = index % perLayer;
    ivec3 at = ivec3(texel % uMapSize, texel / uMapSize, light);
    vec4 p = texelFetch(uSssDirPosition, at, 0);
    s.position = p.xyz;
    s.tag = int(p.w + 0.5);
    s.normal = texelFetch(uSssDirNormal, at, 0).xyz;
    toLight = uSssDirDirection[light];
    // Φ_p = E A_p, A_p the texel's area on the light's view plane: world → [0, 1] scales x and y
    // by 1/width and 1/height of the view.
    mat4 m = uSssDirMatrix[light];
    float width = 1.0 / length(vec3(m[0][0], m[1][0], m[2][0]));
    float height = 1.0 / length(vec3(m[0][1], m[1][1], m[2][1]));
    flux = uSssDirIrradiance[light] * (width * height / float(perLayer));
  } else {
    index -= uSssDirCount * perLayer;
    int light = index / (6 * perLayer), face = (index / perLayer) % 6, texel = index % perLayer;
    if (light >= uSssPointCount) return;
    vec3 r = cubeTexelDirection(face, texel % uMapSize, texel / uMapSize);
    vec4 p = textureLod(uSssPointGPosition, vec4(r, float(light)), 0.0);
    s.position = p.xyz;
    s.tag = int(p.w + 0.5);
    s.normal = textureLod(uSssPointGNormal, vec4(r, float(light)), 0.0).xyz;
    toLight = normalize(uSssPointPosition[light] - s.position);
    // Φ_p = I Δω_p, a 90° face (tan(FOV/2) = 1, α = 1): Δω_p = 4 cos³θ_p / N², cos θ_p = 1/|r|.
    flux = uSssPointIntensity[light] * sslpvTexelSolidAngle(1.0 / length(r), 1.0, 1.0, float(uMapSize), float(uMapSize));
  }
  if (s.tag < 1) return;  // no translucent surface here (nothing, or an opaque occluder)
  vec3 n = normalize(s.normal);
  float cosI = dot(n, toLight);
  if (cosI <= 0.0) return;  // the light grazes or is behind this surface
  float eta = uSlotEta[s.tag - 1];
  float t = fresnelTransmittance(cosI, eta);
  vec3 wt = refractedDirection(toLight, n, eta);  // ω_t, into the medium (Snell)
  // The cell half a cell inside the surface: the one the light enters through x_p.
  vec3 g = (s.position - 0.5 * uGridCell * n - uGridOrigin) / uGridCell;
  ivec3 cell = ivec3(floor(g));
  if (any(lessThan(cell, ivec3(0))) || any(greaterThanEqual(cell, ivec3(uGridSize)))) return;
  vCell = cell;
  vR = sslpvInjectedIntensity(t * flux.r, wt);  // Eq. 1 on the SH
  vG = sslpvInjectedIntensity(t * flux.g, wt);
  vB = sslpvInjectedIntensity(t * flux.b, wt);
}
