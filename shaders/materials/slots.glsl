// The translucent slots of a frame (sss/translucent_slots.h): each translucent object has a slot,
// and an object with a liquid part (the candle's pool, materials/liquid_surface.glsl) a second one
// for it, with its own material. Light scatters between the slots of one object (the pool and the
// wax are one body); a surface point's slot is its object's, or the liquid's where the point lies
// on the liquid (surfaceSlot). Tags in the G-buffers are slot + 1 (0: opaque or nothing).
#include "materials/liquid_surface.glsl"

const int SSS_MAX_SLOTS = 8;
uniform int uSlotObject[SSS_MAX_SLOTS];          // which object (its index) a slot belongs to
uniform int uSlotLiquid[SSS_MAX_SLOTS];          // the liquid slot of a slot's object, −1: none
uniform vec4 uSlotLiquidRegion[SSS_MAX_SLOTS];   // liquidSurfaceContains's region, object units
uniform mat4 uSlotWorldToObject[SSS_MAX_SLOTS];  // world → object (a field's transform is rigid)
uniform float uSlotEta[SSS_MAX_SLOTS];           // η of each slot's material

// The slot of a surface point of the object whose main slot is `slot` (world position and normal).
int surfaceSlot(int slot, vec3 worldPosition, vec3 worldNormal) {
  if (slot < 0 || slot >= SSS_MAX_SLOTS) return slot;
  int liquid = uSlotLiquid[slot];
  if (liquid < 0) return slot;
  mat4 toObject = uSlotWorldToObject[slot];
  vec3 p = (toObject * vec4(worldPosition, 1.0)).xyz;
  vec3 n = mat3(toObject) * worldNormal;
  return liquidSurfaceContains(p, n, uSlotLiquidRegion[slot]) ? liquid : slot;
}

// True when tag (slot + 1 of a G-buffer) is a surface of the same object as `slot`.
bool sameObjectTag(int tag, int slot) {
  return tag >= 1 && tag <= SSS_MAX_SLOTS && uSlotObject[tag - 1] == uSlotObject[slot];
}
