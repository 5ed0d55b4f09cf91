// What the camera's coverage target says of a pixel (r translucent, g seen by a map, b opaque, a
// halved where the candle's flame is drawn in front), shared with C++ (sss::pixelMasksOf).
#include "common/shared.glsl"

// A translucent object seen, no flame in front of it.
TALLOW_FN bool seesTranslucent(vec4 c) { return c.r > 0.5f && c.a > 0.75f; }
// An opaque surface seen: a receiver of the VPLs' light.
TALLOW_FN bool seesReceiver(vec4 c) { return c.b > 0.5f; }

// Both as one number, 1 (translucent) + 2 (receiver): the alpha of the picture shown after the glare
// or the local exposure, so that a capture reads the masks back with that picture instead of
// reading the coverage target too (issue 39, point 4: at most two targets a frame).
TALLOW_FN float coverageCode(vec4 c) { return (seesTranslucent(c) ? 1.0f : 0.0f) + (seesReceiver(c) ? 2.0f : 0.0f); }
