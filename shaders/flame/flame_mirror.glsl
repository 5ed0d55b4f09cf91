// The candle's flame seen in a mirror (issue 35: the melt pool's flat surface reflects it), written
// once for GLSL and C++ (the conventions of shaders/bssrdf/real.glsl): what the flame's sheet shows
// to a viewer at `origin` looking along unit `dir`. The sheet is drawn facing each viewer
// (shaders/flame.vert: it contains the axis through the flame's centre and turns to the camera), so a
// reflected ray meets the sheet the flame would turn toward its origin: the plane through the axis
// facing `origin`, at height v = (p − base)·up / height, across x = (p − base − v² sway)·side in
// half-widths. Returns flameProfile there (0 where the ray misses it, runs away from it or starts on
// the axis); the caller scales it to the drawn flame's radiance. No occlusion test here: the callers
// weight it by whether the flame's light reaches the origin (surface.frag: that light's shadow map;
// the reference: a shadow ray), since a ray from the puddle at the candle's foot meets the sheet
// through the wax (two orange dots on the default picture's puddle, issue 36).
#ifdef TALLOW_GLSL
#include "flame/flame_profile.glsl"
#endif

TALLOW_FN real3 flameSeenAlong(real3 origin, real3 dir, real3 base, real3 up, real height, real halfWidth, real3 sway) {
  real3 centre = base + real(0.4) * height * up;  // as flame.vert turns the sheet about
  real3 toViewer = origin - centre;
  real3 m = toViewer - dot(toViewer, up) * up;
  real mLength = length(m);
  if (!(mLength > real(1e-9)) || !(height > real(0)) || !(halfWidth > real(0))) return real3(real(0));
  m = m / mLength;
  real approach = dot(dir, m);
  if (!(approach < real(0))) return real3(real(0));
  real t = dot(base - origin, m) / approach;
  if (!(t > real(0))) return real3(real(0));
  real3 p = origin + t * dir;
  real v = dot(p - base, up) / height;
  if (v < real(0) || v > FLAME_TIP_REACH) return real3(real(0));
  real3 side = cross(up, m);
  real x = dot(p - base - v * v * sway, side) / halfWidth;
  return flameProfile(x, v);
}
