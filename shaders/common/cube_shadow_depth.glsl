// What a point light's cube shadow map holds and what a receiver compares with it, shared with
// C++ (sss/shadow_pass.cpp places the near plane with the same constant).
//
// Each face is rasterised through a 90° perspective projection with near plane n = fraction × range
// and far plane f = range (cubeFaceViewProjections), so a point whose offset from the light has
// the face's axis component m lands at window depth f (m − n) / ((f − n) m) (glm::perspective's
// clip z in [−1, 1], mapped by 0.5 z + 0.5). The cube look-up picks the face by the largest
// component of the same offset, so the receiver's reference is that depth for m = max |d_i|: the
// shadow pass needs no fragment shader writing gl_FragDepth and keeps early depth (issue 39).
// Resolution: dd/dm = f n / ((f − n) m²), so the normal offset of one texel (θ m, the least the
// receivers add) moves the depth by ≈ 1e-3 θ range / m: at the far plane 13 float steps for 1024²
// faces (θ = 1.5 mrad), 1.6 for the largest (8192²), whatever the range
// (tests/cube_shadow_depth_test.cpp).
#include "common/shared.glsl"

const float kCubeShadowNearFraction = 1e-3f;

TALLOW_FN float cubeShadowDepth(vec3 d, float range) {
  float m = max(max(abs(d.x), abs(d.y)), abs(d.z));
  float n = kCubeShadowNearFraction * range;
  return range * (m - n) / ((range - n) * m);
}

// The inverse: the largest axis component m of the offset whose window depth is z (a depth the
// shadow map stores), m = f n / (f − z (f − n)): how far along the face's axis the first surface
// the light sees lies (method=burley's thickness through the object, sss/peers/burley.h).
TALLOW_FN float cubeShadowAxisDistance(float z, float range) {
  float n = kCubeShadowNearFraction * range;
  return range * n / (range - z * (range - n));
}
