#version 450 core
// The view window's debug views of textures (sss/debug_view_pass.h): a light's G-buffer, a
// scattered radiosity map, Algorithm 1's coverage, the difference to a reference image.
#include "common/tonemap.glsl"

in vec2 vUv;

const int MODE_GBUFFER_POSITION = 0;
const int MODE_GBUFFER_NORMAL = 1;
const int MODE_MAP = 2;
const int MODE_COVERAGE = 3;
const int MODE_DIFFERENCE = 4;

uniform int uMode;
uniform vec2 uViewport;     // window size in pixels
uniform float uLeft;        // pixels on the left the panel covers: a square is centred right of them
uniform int uSquare;        // 1: a square texture, shown letterboxed in the window
uniform int uCube;          // G-buffer views: 1 reads face uFace of cube uLayer of uCubes
uniform int uLayer;         // array layer (directional G-buffer, map k) or cube index
uniform int uFace;          // cube face 0-5 (+X, -X, +Y, -Y, +Z, -Z)
uniform vec3 uCentre;       // positions: shown as (p - centre) / (2 radius) + 1/2
uniform float uRadius;
uniform float uMapScale;    // maps: 1 / (π F), B summed over F frames → B / π
uniform float uExposureScale;
uniform int uToneMap;
layout(binding = 0) uniform sampler2DArray uLayers;    // G-buffer positions, or the maps
layout(binding = 1) uniform samplerCubeArray uCubes;   // point-light G-buffer positions
layout(binding = 4) uniform sampler2DArray uLayerNormals;
layout(binding = 5) uniform samplerCubeArray uCubeNormals;
layout(binding = 2) uniform sampler2D uImage;
layout(binding = 3) uniform sampler2D uReference;

layout(location = 0) out vec4 oColor;

const vec3 BACKDROP = vec3(0.08);
const float OCCLUDER_DIM = 0.3;  // opaque surfaces in the light's G-buffer: shown, but in the back

// Direction of texture coordinate (s, t) in [0,1]² of a cube face (the GL specification's table
// of cube-map face selection, inverted).
vec3 cubeDirection(int face, vec2 st) {
  float sc = 2.0 * st.x - 1.0, tc = 2.0 * st.y - 1.0;
  if (face == 0) return vec3(1.0, -tc, -sc);
  if (face == 1) return vec3(-1.0, -tc, sc);
  if (face == 2) return vec3(sc, 1.0, tc);
  if (face == 3) return vec3(sc, -1.0, -tc);
  if (face == 4) return vec3(sc, -tc, 1.0);
  return vec3(-sc, -tc, -1.0);
}

vec4 positionTexel(vec2 st) {
  if (uCube != 0) return texture(uCubes, vec4(cubeDirection(uFace, st), float(uLayer)));
  return textureLod(uLayers, vec3(st, float(uLayer)), 0.0);
}

vec4 normalTexel(vec2 st) {
  if (uCube != 0) return texture(uCubeNormals, vec4(cubeDirection(uFace, st), float(uLayer)));
  return textureLod(uLayerNormals, vec3(st, float(uLayer)), 0.0);
}

void main() {
  vec2 st = vUv;
  if (uSquare != 0) {
    // The largest centred square, the texture upright as its camera saw it.
    vec2 free = vec2(uViewport.x - uLeft, uViewport.y);
    float side = min(free.x, free.y);
    vec2 corner = vec2(uLeft, 0.0) + 0.5 * (free - vec2(side));
    st = (gl_FragCoord.xy - corner) / side;
    if (any(lessThan(st, vec2(0.0))) || any(greaterThan(st, vec2(1.0)))) {
      oColor = vec4(BACKDROP, 1.0);
      return;
    }
  }
  vec3 c = BACKDROP;
  if (uMode == MODE_GBUFFER_POSITION || uMode == MODE_GBUFFER_NORMAL) {
    // Texels no surface covers were cleared to zero (a zero normal). Position w: the translucent
    // object's tag (slot + 1), 0 for opaque occluders, which are shown dimmed.
    vec4 p = positionTexel(st);
    vec3 n = normalTexel(st).xyz;
    bool covered = length(n) > 0.5;
    bool translucent = p.w > 0.0;
    if (uMode == MODE_GBUFFER_NORMAL) c = covered ? (0.5 * n + 0.5) * (translucent ? 1.0 : OCCLUDER_DIM) : BACKDROP;
    else if (translucent) c = clamp((p.xyz - uCentre) / (2.0 * uRadius) + 0.5, 0.0, 1.0);
    else c = covered ? vec3(0.25) : BACKDROP;
    oColor = vec4(c, 1.0);
    return;
  }
  if (uMode == MODE_MAP) {
    vec3 b = textureLod(uLayers, vec3(st, float(uLayer)), 0.0).rgb * uMapScale;
    oColor = vec4(toneMapToSrgb(b, uExposureScale, uToneMap), 1.0);
    return;
  }
  if (uMode == MODE_COVERAGE) {
    vec4 k = texture(uImage, st);
    // Seen by some map: green; translucent but seen by none (B = 0): red; opaque: grey-blue.
    c = k.r > 0.5 ? (k.g > 0.5 ? vec3(0.15, 0.8, 0.2) : vec3(0.9, 0.1, 0.1)) : (k.b > 0.5 ? vec3(0.2, 0.25, 0.4) : BACKDROP);
    oColor = vec4(c, 1.0);
    return;
  }
  // MODE_DIFFERENCE: signed, luminance-weighted, tone mapped like radiance: red where the image is
  // brighter than the reference, blue where it is darker.
  vec3 d = texture(uImage, st).rgb - texture(uReference, st).rgb;
  float signedLuminance = dot(d, vec3(0.2126, 0.7152, 0.0722));
  float m = toneMapToSrgb(vec3(abs(signedLuminance)), uExposureScale, uToneMap).r;
  oColor = vec4(signedLuminance > 0.0 ? vec3(m, 0.0, 0.0) : vec3(0.0, 0.0, m), 1.0);
}
