// Emergent light on opaque receivers from the VPLs (the radiosity-maps paper's Eq. 15 with the
// intensity of Eq. 16): each VPL is a patch of area A_v and radiance F_t(θ_v) B(x_v)/π, so its
// irradiance at p is F_t(θ_v) (B/π) A_v cos θ_v cos θ_r G_b. The bounded geometry term
// G_b = 1 / (d² + A_v/π) is the exact on-axis value for a disc of area A_v (E = πL R²/(d² + R²)),
// so a receiver next to a VPL sees at most the radiance of the surface it stands for, never the
// 1/d² spike of a point.
#include "bssrdf/fresnel.glsl"
#include "common/lights.glsl"
#include "maps/vpl_record.glsl"

layout(std430, binding = 6) readonly buffer VplRecords { VplGpu vplRecords[]; };
layout(std430, binding = 8) readonly buffer VplPartRecords { VplGpu vplParts[]; };  // VPL_PARTS per VPL
uniform int uVplCount;  // 0: no VPLs this frame
uniform vec3 uVplCentre;  // c, the point the VPLs' directions start from (maps/vpl.comp)

// VPL shadows (vpl.shadows): each VPL's cluster has a cube shadow map (common/cube_shadow_depth.glsl)
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
  return texture(uVplShadow, vec4(dq, float(uVplClusterCube[c])), cubeShadowDepth(dq, range));
}

// A VPL's irradiance at p as a point: F_t(θ_v) (B/π) A_v cos θ_v cos θ_r / (d² + A_v/π).
vec3 vplPointIrradiance(VplGpu l, vec3 p, vec3 n) {
  vec3 toP = p - l.position.xyz;
  float d2 = dot(toP, toP);
  vec3 w = toP * inversesqrt(max(d2, 1e-30));
  float cosV = dot(l.normal.xyz, w), cosR = -dot(n, w);
  if (cosV <= 0.0 || cosR <= 0.0) return vec3(0.0);
  float area = l.normal.w;
  return fresnelTransmittance(cosV, l.position.w) * l.radiance.rgb * (area * cosV * cosR / (d2 + area / 3.14159265358979));
}

// Near a VPL the point is a poor stand-in for the surface it represents: the integrand of a wall
// seen from the table at its foot grows as 1/d⁴. There the VPL is the patch it stands for, of
// uniform radiance F_t(θ_v) B/π, whose irradiance is exact by Lambert's polygon formula,
// E = L/2 Σ_i Θ_i (n · γ_i) (Θ_i: the angle the edge i subtends at p, γ_i: the unit normal of the
// plane through p and that edge), after clipping the patch to p's upper hemisphere. The patch is
// what a square of solid angle around the VPL's direction from c covers on the surface: a rectangle
// of area A_v, longer by 1/cos α along the tilt of the surface away from c (maps/vpl.comp's weight).
vec3 vplSquareIrradiance(VplGpu l, vec3 p, vec3 n) {
  vec3 x = l.position.xyz, nv = l.normal.xyz;
  vec3 toP = p - x;
  float d2 = dot(toP, toP);
  float cosV = dot(nv, toP) * inversesqrt(max(d2, 1e-30));
  if (cosV <= 0.0) return vec3(0.0);  // behind the patch
  vec3 r = x - uVplCentre;
  vec3 tilt = r - dot(r, nv) * nv;
  float cosAlpha = max(abs(dot(nv, normalize(r))), VPL_MIN_COS_ALPHA);
  vec3 t1 = dot(tilt, tilt) > 1e-12 * dot(r, r) ? normalize(tilt) : vplPerpendicular(nv);
  vec3 t2 = cross(nv, t1);
  float h1 = 0.5 * sqrt(l.normal.w / cosAlpha), h2 = 0.5 * sqrt(l.normal.w * cosAlpha);
  vec3 corner[4] = vec3[4](x - h1 * t1 - h2 * t2, x + h1 * t1 - h2 * t2, x + h1 * t1 + h2 * t2, x - h1 * t1 + h2 * t2);
  // Sutherland–Hodgman against the plane dot(n, q - p) = 0, keeping the side above it.
  vec3 poly[5];
  int count = 0;
  for (int i = 0; i < 4; ++i) {
    vec3 a = corner[i] - p, b = corner[(i + 1) % 4] - p;
    float da = dot(n, a), db = dot(n, b);
    if (da > 0.0) poly[count++] = a;
    if ((da > 0.0) != (db > 0.0)) poly[count++] = a + (b - a) * (da / (da - db));
  }
  if (count < 3) return vec3(0.0);
  float sum = 0.0;
  for (int i = 0; i < count; ++i) {
    vec3 a = normalize(poly[i]), b = normalize(poly[(i + 1) % count]);
    vec3 c = cross(a, b);
    float len = length(c);
    if (len < 1e-9) continue;
    sum += atan(len, dot(a, b)) * dot(n, c / len);  // Θ_i by atan2: acos loses it in float for short edges
  }
  return fresnelTransmittance(cosV, l.position.w) * l.radiance.rgb * (0.5 * abs(sum));
}

// From VPL_FAR to VPL_NEAR sides (√A) away from a record, its point gives way to its patch,
// smoothly (no ring where the two meet); from VPL_PARTS_FAR to VPL_PARTS_NEAR sides of a VPL, the
// VPL gives way to its cell's parts. The parts' distances were chosen on the candle holder at 80
// VPLs (docs/vpl.md): 1–2 sides 7.4% receiver error, 1.5–3 6.9%, 2–4 6.6% at 1.4× the camera pass
// of 1.5–3. tests/vpl_gltest.cpp mirrors the blends.
const float VPL_NEAR = 2.0, VPL_FAR = 4.0;
const float VPL_PARTS_NEAR = 1.5, VPL_PARTS_FAR = 3.0;

float vplNearness(VplGpu l, vec3 p, float nearSides, float farSides) {
  float sides = length(p - l.position.xyz) * inversesqrt(max(l.normal.w, 1e-30));
  return 1.0 - smoothstep(nearSides, farSides, sides);
}

vec3 vplPointOrPatch(VplGpu l, vec3 p, vec3 n) {
  float near = vplNearness(l, p, VPL_NEAR, VPL_FAR);
  vec3 e = vec3(0.0);
  if (near < 1.0) e += (1.0 - near) * vplPointIrradiance(l, p, n);
  if (near > 0.0) e += near * vplSquareIrradiance(l, p, n);
  return e;
}

// Irradiance at receiver point p (normal n) from all VPLs [W/m²]. Near a VPL its parts stand in
// for it: one patch of one radiance is a poor stand-in for a surface whose radiance changes across
// the cell (a wall darkening toward its foot), and the cells' rectangles do not tile the surface,
// which a receiver within a side of it would show as scallops.
vec3 vplIrradiance(vec3 p, vec3 n) {
  vec3 e = vec3(0.0);
  for (int v = 0; v < uVplCount; ++v) {
    VplGpu l = vplRecords[v];
    if (l.position.w <= 0.0) continue;  // inactive
    float near = vplNearness(l, p, VPL_PARTS_NEAR, VPL_PARTS_FAR);
    vec3 term = vec3(0.0);
    if (near < 1.0) term += (1.0 - near) * vplPointIrradiance(l, p, n);
    if (near > 0.0) {
      vec3 parts = vec3(0.0);
      for (int k = 0; k < VPL_PARTS; ++k) {
        VplGpu part = vplParts[v * VPL_PARTS + k];
        if (part.position.w > 0.0) parts += vplPointOrPatch(part, p, n);
      }
      term += near * parts;
    }
    e += term * vplVisibility(v, p, n);
  }
  return e;
}
