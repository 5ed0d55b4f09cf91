#version 450 core
// image_space.gbuffer: the camera's view of every object (drawn with surface.vert, so its fragments
// are the surface pass's), keeping per pixel what the scatter pass reads (the image-space paper's
// §6.2: the irradiance texture and the depth of the camera view):
//   position: the world point [m] and, in w, the translucent slot + 1 (0: opaque);
//   normal:   the normal on the side facing the camera (open meshes show their inside, as surface.frag);
//   irradiance: E(x_i) = Σ_ℓ E_ℓ cos θ_ℓ F_t(cos θ_ℓ) V_ℓ (Eq. 5 for the scene's lights, V_ℓ their
//   shadow maps), the light transmitted into the medium; the ambient sky enters no subsurface
//   term in Tallow (it is reflected specularly, as for the other methods and the reference).
#include "common/lights.glsl"
#include "bssrdf/fresnel.glsl"

in vec3 vWorldPosition;
in vec3 vWorldNormal;

uniform int uSlot;  // translucent slot of the object, −1 for an opaque one
uniform float uObjectEta;
uniform vec3 uCameraPosition;
uniform int uCameraOrthographic;
uniform vec3 uCameraForward;

layout(location = 0) out vec4 oPosition;
layout(location = 1) out vec4 oNormal;
layout(location = 2) out vec4 oIrradiance;

void main() {
  vec3 n = normalize(vWorldNormal);
  vec3 toCamera = uCameraOrthographic != 0 ? -uCameraForward : uCameraPosition - vWorldPosition;
  if (dot(n, toCamera) < 0.0) n = -n;
  vec3 p = vWorldPosition;
  oPosition = vec4(p, float(uSlot + 1));
  oNormal = vec4(n, 0.0);
  vec3 e = vec3(0.0);
  if (uSlot >= 0) {
    for (int i = 0; i < uDirCount; ++i) {
      float c = dot(n, uDirDirection[i]);
      if (c > 0.0) e += uDirIrradiance[i] * (c * fresnelTransmittance(c, uObjectEta)) * directionalVisibility(i, p, n);
    }
    for (int i = 0; i < uPointCount; ++i) {
      vec3 l = uPointPosition[i] - p;
      float d2 = dot(l, l);
      float c = dot(n, l) * inversesqrt(d2);
      if (c > 0.0)
        e += uPointIntensity[i] * (c * fresnelTransmittance(c, uObjectEta) / d2) * pointVisibility(i, p, n);
    }
  }
  oIrradiance = vec4(e, 0.0);
}
