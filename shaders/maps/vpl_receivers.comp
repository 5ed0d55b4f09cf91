#version 450 core
// The VPLs' emergent light on the opaque receivers (the radiosity-maps paper's Eq. 15, with the
// irradiance of maps/vpl_receiver.glsl), once per pixel of the camera target after the camera pass,
// in compute rather than in the camera pass's fragment shader: the camera pass leaves each opaque
// pixel's point, normal and albedo (surface.frag's receiver targets), and this pass adds
// ρ/π · E_vpl to its radiance. The same sum the fragment path makes (VplReceivers.* compares them).
layout(local_size_x = 8, local_size_y = 8) in;

#include "common/octahedral.glsl"
#include "maps/vpl_receiver.glsl"

layout(rgba32f, binding = 0) uniform image2D uRadiance;
uniform usampler2D uReceiver;       // xyz: world point's float bits, w: its unit normal (packOctahedral)
uniform sampler2D uReceiverAlbedo;  // rgb: ρ, a: 1 on an opaque receiver, 0 elsewhere

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(px, imageSize(uRadiance)))) return;
  vec4 albedo = texelFetch(uReceiverAlbedo, px, 0);
  if (albedo.a == 0.0) return;
  uvec4 receiver = texelFetch(uReceiver, px, 0);
  vec3 e = vplIrradiance(uintBitsToFloat(receiver.xyz), unpackOctahedral(receiver.w));
  vec4 radiance = imageLoad(uRadiance, px);
  imageStore(uRadiance, px, vec4(radiance.rgb + albedo.rgb / 3.14159265358979 * e, radiance.a));
}
