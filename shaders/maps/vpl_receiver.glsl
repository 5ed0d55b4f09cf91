// Emergent light on opaque receivers from the VPLs (the radiosity-maps paper's Eq. 15 with the
// intensity of Eq. 16): each VPL is a patch of area A_v and radiance F_t(θ_v) B(x_v)/π, so its
// irradiance at p is F_t(θ_v) (B/π) A_v cos θ_v cos θ_r G_b. The bounded geometry term
// G_b = 1 / (d² + A_v/π) is the exact on-axis value for a disc of area A_v (E = πL R²/(d² + R²)),
// so a receiver next to a VPL sees at most the radiance of the surface it stands for, never the
// 1/d² spike of a point.
#include "bssrdf/fresnel.glsl"
#include "common/lights.glsl"

struct VplGpu { vec4 position; vec4 normal; vec4 radiance; };  // sss::VplRecord
layout(std430, binding = 6) readonly buffer VplRecords { VplGpu vplRecords[]; };
uniform int uVplCount;  // 0: no VPLs this frame

// VPL shadows (vpl.shadows): each VPL's cluster has a cube shadow map (distance / range as depth)
// from a camera just outside the cluster's VPLs; the receiver is tested against it, with the
// normal offset of the point lights' shadows (common/lights.glsl).
const int MAX_VPL_CLUSTERS = 64;
uniform int uVplShadows;
uniform samplerCubeArrayShadow uVplShadow;
uniform vec3 uVplClusterCentre[MAX_VPL_CLUSTERS];
uniform float uVplClusterRange[MAX_VPL_CLUSTERS];  // 0: no shadow map
uniform int uVplClusterCube[MAX_VPL_CLUSTERS];
uniform float uVplShadowTexelAngle;

float vplVisibility(int v, vec3 p, vec3 n) {
  if (uVplShadows == 0) return 1.0;
  int c = clamp(int(vplRecords[v].radiance.w + 0.5), 0, MAX_VPL_CLUSTERS - 1);
  float range = uVplClusterRange[c];
  if (range <= 0.0) return 1.0;
  vec3 centre = uVplClusterCentre[c];
  vec3 q = p + n * (normalOffsetTexels() * uVplShadowTexelAngle * length(p - centre));
  vec3 dq = q - centre;
  return texture(uVplShadow, vec4(dq, float(uVplClusterCube[c])), length(dq) / range);
}

// Irradiance at receiver point p (normal n) from all VPLs [W/m²].
vec3 vplIrradiance(vec3 p, vec3 n) {
  vec3 e = vec3(0.0);
  for (int v = 0; v < uVplCount; ++v) {
    VplGpu l = vplRecords[v];
    if (l.position.w <= 0.0) continue;  // inactive
    vec3 toP = p - l.position.xyz;
    float d2 = dot(toP, toP);
    vec3 w = toP * inversesqrt(max(d2, 1e-30));
    float cosV = dot(l.normal.xyz, w), cosR = -dot(n, w);
    if (cosV <= 0.0 || cosR <= 0.0) continue;
    float area = l.normal.w;
    e += fresnelTransmittance(cosV, l.position.w) * l.radiance.rgb * (area * cosV * cosR / (d2 + area / 3.14159265358979)) *
         vplVisibility(v, p, n);
  }
  return e;
}
