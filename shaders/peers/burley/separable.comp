#version 450 core
// burley.scatter with burley.kernel=separable (sss/peers/burley.h): the profile applied as two 1D
// passes in screen space, horizontal then vertical, as Jimenez et al.'s separable subsurface
// scattering (2015) does, with this profile's taps: per slot 2K + 1 taps at offsets ±t_k [mm]
// along the pass's axis, each weighing the profile's mass in its strip of the plane per band
// (sss/peers/burley_profile.h burleySeparableTaps; the weights of a band sum to 1). The world
// offsets are projected into pixels at x_o's depth. "Follow the surface" as the paper's kernel does:
// a tap on another object takes x_o's own value, and a tap whose surface point lies off the
// expected distance moves toward it by |distance − t| / d_max. The second pass multiplies by A and
// adds the light through thin parts (transmission.glsl).
#include "peers/burley/transmission.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = 0) writeonly uniform image2D uRadiosity;

struct BurleyTapGpu {
  vec4 weightOffset;  // rgb: weight per band; a: t_k [mm]
};
layout(std430, binding = 8) readonly buffer Taps { BurleyTapGpu taps[]; };

uniform sampler2D uInput;  // pass 0: E F_t (the G-buffer's irradiance); pass 1: pass 0's result
uniform int uPass;         // 0: along x; 1: along y, then × A and the transmitted light
uniform int uHalfTaps;     // K
uniform int uTapStride;    // entries per slot in taps[]

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = textureSize(uPosition, 0);
  if (any(greaterThanEqual(px, size))) return;
  vec4 centre = texelFetch(uPosition, px, 0);
  int slot = int(centre.w + 0.5) - 1;
  if (slot < 0 || slot >= BURLEY_MAX_SLOTS) {
    imageStore(uRadiosity, px, vec4(0.0));
    return;
  }
  vec3 xo = centre.xyz;
  BurleyBand b0 = slotBand(slot, 0), b1 = slotBand(slot, 1), b2 = slotBand(slot, 2);
  float dMax = max(max(b0.d, b1.d), b2.d);  // [mm]
  float footprint = pixelFootprint(xo);
  vec2 axis = uPass == 0 ? vec2(1.0, 0.0) : vec2(0.0, 1.0);
  vec3 own = texelFetch(uInput, px, 0).rgb;
  vec3 sum = own * taps[slot * uTapStride].weightOffset.rgb;
  for (int k = 1; k <= uHalfTaps; ++k) {
    vec4 tap = taps[slot * uTapStride + k].weightOffset;
    for (int side = -1; side <= 1; side += 2) {
      ivec2 q = ivec2(floor(vec2(px) + 0.5 + float(side) * (tap.a / BURLEY_MM_PER_M / footprint) * axis));
      vec3 value = own;
      if (all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, size))) {
        vec4 hit = texelFetch(uPosition, q, 0);
        if (int(hit.w + 0.5) == slot + 1) {
          float off = abs(length(hit.xyz - xo) * BURLEY_MM_PER_M - tap.a);
          value = mix(texelFetch(uInput, q, 0).rgb, own, clamp(off / dMax, 0.0, 1.0));
        }
      }
      sum += value * tap.rgb;
    }
  }
  if (uPass == 0) {
    imageStore(uRadiosity, px, vec4(sum, 1.0));
    return;
  }
  vec3 b = sum * vec3(b0.albedo, b1.albedo, b2.albedo);
  if (uTransmission != 0) b += transmitted(xo, normalize(texelFetch(uNormal, px, 0).xyz), uEta[slot], b0, b1, b2);
  imageStore(uRadiosity, px, vec4(b, 1.0));
}
