// Where a translucent object's surface is liquid (issue 35): the melting candle's pool. Written once
// for GLSL and C++ (the conventions of shaders/bssrdf/real.glsl); every pass that needs a surface
// point's material (the light and map G-buffers, the gather, the camera pass, the VPLs, the CPU
// reference) asks this, so that they agree on every point.
//
// The region is in the object's own units (field units of a candle: metres, y up the axis):
// (y of the pool's flat free surface, its radius, the meniscus's height above it, a tolerance).
// A point belongs to the liquid when it lies on the free surface or the meniscus that rises from it
// to the wall — within the tolerance of the surface's height, inside the radius — and its normal
// faces up (the wick standing in the pool and the cup's wall above it stay wax). Radius 0: no pool.
#ifdef TALLOW_GLSL
#include "common/shared.glsl"
#include "bssrdf/real.glsl"
#endif

// The smallest up-component of a liquid surface's normal: the meniscus turns from up to the wall;
// its steepest part (beyond 75°) is counted as wall.
const real LIQUID_MIN_UP = 0.25;

TALLOW_FN bool liquidSurfaceContains(real3 p, real3 n, real4 region) {
  real poolY = region.x, radius = region.y, meniscus = region.z, tol = region.w;
  if (!(radius > real(0))) return false;
  if (p.y < poolY - tol || p.y > poolY + meniscus + tol) return false;
  if (p.x * p.x + p.z * p.z > (radius + tol) * (radius + tol)) return false;
  real len = length(n);
  return len > real(0) && n.y >= LIQUID_MIN_UP * len;
}
