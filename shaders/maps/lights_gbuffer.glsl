// The lights as the radiosity-map passes see them: their G-buffers (step 1) and parameters.
const int SSS_MAX_DIRECTIONAL = 32;
const int SSS_MAX_POINT = 8;

uniform int uSssDirCount;
uniform vec3 uSssDirDirection[SSS_MAX_DIRECTIONAL];   // unit, toward the light
uniform vec3 uSssDirIrradiance[SSS_MAX_DIRECTIONAL];  // W/m² on a surface facing the light
uniform mat4 uSssDirMatrix[SSS_MAX_DIRECTIONAL];      // world → [0,1]³ of its G-buffer layer
uniform vec3 uSssDirTangent[SSS_MAX_DIRECTIONAL];     // first basis vector of its view plane
uniform vec3 uSssDirBitangent[SSS_MAX_DIRECTIONAL];   // second basis vector

uniform int uSssPointCount;
uniform vec3 uSssPointPosition[SSS_MAX_POINT];   // m
uniform vec3 uSssPointIntensity[SSS_MAX_POINT];  // W/sr

uniform sampler2DArray uSssDirPosition;    // xyz: world position [m], w: object tag
uniform sampler2DArray uSssDirNormal;
uniform samplerCubeArray uSssPointGPosition;
uniform samplerCubeArray uSssPointGNormal;

struct GSample {
  vec3 position;  // m
  vec3 normal;
  int tag;        // translucent slot + 1, 0 for opaque or nothing
};

GSample directionalGBuffer(int light, vec3 worldPoint) {
  vec4 t = uSssDirMatrix[light] * vec4(worldPoint, 1.0);
  GSample s;
  s.tag = 0;
  if (any(lessThan(t.xy, vec2(0.0))) || any(greaterThanEqual(t.xy, vec2(1.0)))) return s;
  ivec2 size = textureSize(uSssDirPosition, 0).xy;
  ivec3 texel = ivec3(ivec2(t.xy * vec2(size)), light);
  vec4 p = texelFetch(uSssDirPosition, texel, 0);
  s.position = p.xyz;
  s.tag = int(p.w + 0.5);
  s.normal = texelFetch(uSssDirNormal, texel, 0).xyz;
  return s;
}

GSample pointGBuffer(int light, vec3 direction) {
  vec4 p = textureLod(uSssPointGPosition, vec4(direction, float(light)), 0.0);
  GSample s;
  s.position = p.xyz;
  s.tag = int(p.w + 0.5);
  s.normal = textureLod(uSssPointGNormal, vec4(direction, float(light)), 0.0).xyz;
  return s;
}
