// SSLPV's rendering (the paper's §3.3) for the camera pass: the accumulation grid read half a cell
// inside the surface, rotated into the normal's frame (Eq. 6) and turned into the radiance of an
// area light of one cell's cross-section A = ΔX² (Eqs. 5 and 7). Returns B = π L_i, so that the
// caller's L_o = F_t(ω_o)/π · B is Eq. 7's T(ω_i, ω_o) L_i.
#include "peers/sslpv/sh.glsl"

uniform sampler3D uSslpvAccR;  // accumulation grid per band (SH coefficients)
uniform sampler3D uSslpvAccG;
uniform sampler3D uSslpvAccB;
uniform sampler3D uSslpvMedium;  // a: 1 inside the medium, 0 in vacuum
uniform vec3 uSslpvOrigin;       // m
uniform float uSslpvCell;        // m
uniform float uSslpvCapCos;      // cos θ_c of Eq. 7's cap: 0 the paper's hemisphere, 2/3 one face

// `seen` is 0 where no medium cell lies around the look-up point.
vec3 sslpvRadiosity(vec3 xo, vec3 n, out float seen) {
  // Half a cell inside, where the cells hold the light about to leave through x_o. Trilinear
  // weights over medium cells only: the accumulation of vacuum cells is 0, so dividing by the
  // interpolated medium flag renormalises the weights to the cells inside.
  vec3 size = vec3(textureSize(uSslpvAccR, 0));
  vec3 uvw = (xo - 0.5 * uSslpvCell * n - uSslpvOrigin) / (uSslpvCell * size);
  float medium = textureLod(uSslpvMedium, uvw, 0.0).a;
  seen = medium > 1e-4 ? 1.0 : 0.0;
  if (medium <= 1e-4) return vec3(0.0);
  float area = uSslpvCell * uSslpvCell;
  vec3 b;
  b.r = sslpvAreaLightRadiance(sslpvRotateToNormal(textureLod(uSslpvAccR, uvw, 0.0) / medium, n), area, uSslpvCapCos);
  b.g = sslpvAreaLightRadiance(sslpvRotateToNormal(textureLod(uSslpvAccG, uvw, 0.0) / medium, n), area, uSslpvCapCos);
  b.b = sslpvAreaLightRadiance(sslpvRotateToNormal(textureLod(uSslpvAccB, uvw, 0.0) / medium, n), area, uSslpvCapCos);
  return SSLPV_PI * max(b, vec3(0.0));
}
