#version 450 core
// The VPLs of a frame (the radiosity-maps paper's §3.4, Eq. 16): one invocation per VPL reads the
// outermost-surface cube map (map_gbuffer.frag drawn from the translucent objects' box centre c,
// farthest surface kept) in its fixed direction, and stores x_v, n_v, the area A_v it stands for,
// and B(x_v)/π from Algorithm 1. The Fresnel factor F_t of Eq. 16 depends on the direction toward
// the receiver, so the receiver applies it (vpl_receiver.glsl).
#include "maps/algorithm1.glsl"
#include "materials/slots.glsl"
#include "maps/vpl_record.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = 6) writeonly buffer Vpls { VplGpu vpls[]; };
layout(std430, binding = 7) readonly buffer Directions { vec4 directions[]; };  // w: shadow cluster
layout(std430, binding = 8) writeonly buffer VplParts { VplGpu vplParts[]; };  // VPL_PARTS per VPL

uniform int uVplCount;                 // N_vpl
uniform vec3 uCentre;                  // c, the cube's centre
uniform samplerCube uCubePosition;     // xyz: surface point [m], w: the surface's slot + 1 (0: none)
uniform samplerCube uCubeNormal;
uniform int uBacklitCount;             // surrounded point lights (placement backlit)
uniform vec3 uBacklitFrom[8];
uniform int uAreaMode;                 // 0: solid angle, 1: bounding box / N_vpl (the paper)
uniform float uBoxArea;                // A of the translucent objects' bounding box [m²]

const float VPL_PI = 3.14159265358979;

// The part k of the cell around d: the cell is taken as the square of solid angle 4π/N centred on
// d, cut into VPL_PART_SIDE² squares on the tangent plane at d (gnomonic); each part's solid angle
// is its square's cos³θ-weighted share of 4π/N, so that the parts' solid angles add up to the cell's.
vec3 partDirection(vec3 d, int k, out float solidAngleShare) {
  vec3 u = vplPerpendicular(d);
  vec3 w = cross(d, u);
  float side = sqrt(4.0 * VPL_PI / float(uVplCount));  // tan of the half side, as a length at unit distance
  float sum = 0.0, mine = 0.0;
  vec3 dk = d;
  for (int j = 0; j < VPL_PART_SIDE; ++j)
    for (int i = 0; i < VPL_PART_SIDE; ++i) {
      vec2 o = side * ((vec2(i, j) + 0.5) / float(VPL_PART_SIDE) - 0.5);
      float cosTheta = inversesqrt(1.0 + dot(o, o));
      float weight = cosTheta * cosTheta * cosTheta;  // dΩ = cos³θ dA on the tangent plane
      sum += weight;
      if (j * VPL_PART_SIDE + i == k) {
        mine = weight;
        dk = normalize(d + o.x * u + o.y * w);
      }
    }
  solidAngleShare = mine / sum;
  return dk;
}

// Invocation i: VPL i / (1 + VPL_PARTS); its record when i % (1 + VPL_PARTS) is 0, else that part.
void main() {
  int i = int(gl_GlobalInvocationID.x);
  int v = i / (1 + VPL_PARTS), k = i % (1 + VPL_PARTS) - 1;
  if (v >= uVplCount) return;
  float share = 1.0;
  vec3 d = k < 0 ? directions[v].xyz : partDirection(directions[v].xyz, k, share);
  vec4 p = texture(uCubePosition, d);
  VplGpu rec;
  rec.position = vec4(0.0);
  rec.normal = vec4(0.0);
  rec.radiance = vec4(0.0);
  int slot = int(p.w + 0.5) - 1;
  if (slot >= 0) {
    vec3 x = p.xyz;
    vec3 n = normalize(texture(uCubeNormal, d).xyz);
    bool backlit = true;
    for (int b = 0; b < uBacklitCount; ++b) backlit = backlit && dot(n, uBacklitFrom[b] - x) <= 0.0;
    if (backlit) {
      vec3 r = x - uCentre;
      float cosAlpha = abs(dot(n, normalize(r)));
      // Directions uniform over the sphere put surface points at density cos α / (4π |r|² N) per
      // unit area, so each stands for 4π |r|² / (N cos α) of the outermost surface (a part: its share).
      float area = share * (uAreaMode == 0 ? 4.0 * VPL_PI * dot(r, r) / (float(uVplCount) * max(cosAlpha, VPL_MIN_COS_ALPHA))
                                           : uBoxArea / float(uVplCount));
      // A VPL stands for A_v of surface: read B averaged over that much, i.e. at the maps' mip level
      // whose footprint is √A_v (Algorithm 1 takes the footprint as two tangent vectors), so that
      // one noisy texel does not become one bright VPL.
      vec3 t1 = vplPerpendicular(n);
      vec3 t2 = cross(n, t1);
      float side = sqrt(area);
      float seenBy = 0.0;
      int firstMap = -1, secondFacingMap = -1;
      vec3 b = scatteredRadiosity(x, n, side * t1, side * t2, seenBy, firstMap, secondFacingMap);
      if (k < 0) countVplCoverage(firstMap);
      rec.position = vec4(x, uSlotEta[slot]);
      rec.normal = vec4(n, area);
      rec.radiance = vec4(b / VPL_PI, directions[v].w);  // w: the shadow cluster
    }
  }
  if (k < 0)
    vpls[v] = rec;
  else
    vplParts[v * VPL_PARTS + k] = rec;
}
