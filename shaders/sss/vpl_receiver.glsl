// Emergent light on opaque receivers from the VPLs (the radiosity-maps paper's Eq. 15 with the
// intensity of Eq. 16): each VPL is a patch of area A_v and radiance F_t(θ_v) B(x_v)/π, so its
// irradiance at p is F_t(θ_v) (B/π) A_v cos θ_v cos θ_r G_b. The bounded geometry term
// G_b = 1 / (d² + A_v/π) is the exact on-axis value for a disc of area A_v (E = πL R²/(d² + R²)),
// so a receiver next to a VPL sees at most the radiance of the surface it stands for, never the
// 1/d² spike of a point.
#include "bssrdf/fresnel.glsl"

struct VplGpu { vec4 position; vec4 normal; vec4 radiance; };  // sss::VplRecord
layout(std430, binding = 6) readonly buffer VplRecords { VplGpu vplRecords[]; };
uniform int uVplCount;  // 0: no VPLs this frame

float vplVisibility(int v, vec3 p, vec3 n) { return 1.0; }

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
