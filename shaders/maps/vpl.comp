#version 450 core
// The VPLs of a frame (the radiosity-maps paper's §3.4, Eq. 16): one invocation per VPL reads the
// outermost-surface cube map (map_gbuffer.frag drawn from the translucent objects' box centre c,
// farthest surface kept) in its fixed direction, and stores x_v, n_v, the area A_v it stands for,
// and B(x_v)/π from Algorithm 1. The Fresnel factor F_t of Eq. 16 depends on the direction toward
// the receiver, so the receiver applies it (vpl_receiver.glsl).
#include "maps/algorithm1.glsl"
#include "materials/slots.glsl"

layout(local_size_x = 64) in;

struct VplGpu { vec4 position; vec4 normal; vec4 radiance; };  // sss::VplRecord
layout(std430, binding = 6) writeonly buffer Vpls { VplGpu vpls[]; };
layout(std430, binding = 7) readonly buffer Directions { vec4 directions[]; };  // w: shadow cluster

uniform int uVplCount;                 // N_vpl
uniform vec3 uCentre;                  // c, the cube's centre
uniform samplerCube uCubePosition;     // xyz: surface point [m], w: the surface's slot + 1 (0: none)
uniform samplerCube uCubeNormal;
uniform int uBacklitCount;             // surrounded point lights (placement backlit)
uniform vec3 uBacklitFrom[8];
uniform int uAreaMode;                 // 0: solid angle, 1: bounding box / N_vpl (the paper)
uniform float uBoxArea;                // A of the translucent objects' bounding box [m²]

const float VPL_PI = 3.14159265358979;
// The solid-angle weight divides by cos α (α between the direction from c and n_v); a VPL seen
// more obliquely than this from c is capped, against single VPLs of unbounded area at silhouettes.
const float MIN_COS_ALPHA = 0.1;

void main() {
  int v = int(gl_GlobalInvocationID.x);
  if (v >= uVplCount) return;
  vec3 d = directions[v].xyz;
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
    for (int i = 0; i < uBacklitCount; ++i) backlit = backlit && dot(n, uBacklitFrom[i] - x) <= 0.0;
    if (backlit) {
      vec3 r = x - uCentre;
      float cosAlpha = abs(dot(n, normalize(r)));
      // Directions uniform over the sphere put surface points at density cos α / (4π |r|² N) per
      // unit area, so each stands for 4π |r|² / (N cos α) of the outermost surface.
      float area = uAreaMode == 0 ? 4.0 * VPL_PI * dot(r, r) / (float(uVplCount) * max(cosAlpha, MIN_COS_ALPHA))
                                  : uBoxArea / float(uVplCount);
      // A VPL stands for A_v of surface: read B averaged over that much, i.e. at the maps' mip level
      // whose footprint is √A_v (Algorithm 1 takes the footprint as two tangent vectors), so that
      // one noisy texel does not become one bright VPL.
      vec3 t1 = normalize(abs(n.y) < 0.9 ? cross(vec3(0.0, 1.0, 0.0), n) : cross(vec3(1.0, 0.0, 0.0), n));
      vec3 t2 = cross(n, t1);
      float side = sqrt(area);
      float seenBy = 0.0;
      int firstMap = -1, secondFacingMap = -1;
      vec3 b = scatteredRadiosity(x, n, side * t1, side * t2, seenBy, firstMap, secondFacingMap);
      countVplCoverage(firstMap);
      rec.position = vec4(x, uSlotEta[slot]);
      rec.normal = vec4(n, area);
      rec.radiance = vec4(b / VPL_PI, directions[v].w);  // w: the shadow cluster
    }
  }
  vpls[v] = rec;
}
