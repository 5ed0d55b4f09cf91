#version 450 core
// The sample pattern of one frame (part of image_space.scatter): for every translucent slot, every
// set of the T×T interleaving tile and every sample j of N, the tangent-plane offset, the balance-
// heuristic weight and the per-band coverage of shaders/peers/image_space/sampling.glsl (the image-space
// paper's §6.2 precomputes the same offsets and weights on the CPU; here the shared lines run on
// the GPU, and tests/image_space_gltest.cpp compares them with their C++ instantiation).
#include "peers/image_space/sampling.glsl"
#include "peers/image_space/pattern.glsl"

layout(local_size_x = 64) in;

const int IS_MAX_SLOTS = 8;
uniform vec3 uSigmaA[IS_MAX_SLOTS];
uniform vec3 uSigmaS[IS_MAX_SLOTS];
uniform vec3 uG[IS_MAX_SLOTS];
uniform float uEta[IS_MAX_SLOTS];
uniform int uSlots;
uniform int uSets;           // T²
uniform int uSamples;        // N
uniform int uUniformSamples; // of N, uniform on the disc
uniform int uFrame;          // accumulated frame: the rotations of the sets
uniform float uRadiusMfp;    // the disc's radius in mean free paths

layout(std430, binding = 7) writeonly buffer Pattern { IsPatternGpu pattern[]; };

void main() {
  int id = int(gl_GlobalInvocationID.x);
  if (id >= uSlots * uSets * uSamples) return;
  int j = id % uSamples;
  int set = (id / uSamples) % uSets;
  int slot = id / (uSamples * uSets);
  BssrdfCoefficients k0 = bssrdfCoefficients(uSigmaA[slot].x, uSigmaS[slot].x, uG[slot].x, uEta[slot]);
  BssrdfCoefficients k1 = bssrdfCoefficients(uSigmaA[slot].y, uSigmaS[slot].y, uG[slot].y, uEta[slot]);
  BssrdfCoefficients k2 = bssrdfCoefficients(uSigmaA[slot].z, uSigmaS[slot].z, uG[slot].z, uEta[slot]);
  IsPatternEntry e = isPatternEntry(k0, k1, k2, uRadiusMfp, j, uSamples, uUniformSamples, uint(set), uint(uFrame));
  pattern[id].offsetWeight = vec4(e.offset, e.weight, 0.0);
  pattern[id].coverage = vec4(e.coverage, 0.0);
}
