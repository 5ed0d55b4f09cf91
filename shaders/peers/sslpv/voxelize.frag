#version 450 core
// SSLPV's solid voxelisation by parity (sss/peers/sslpv_medium.h, step 1; Eisemann and Décoret 2008):
// the translucent objects seen along one grid axis (vLayer: 0 x, 1 y, 2 z) over 2N × 2N columns of
// 2N sub-samples each. A fragment at depth d flips every sub-sample of its column at depth > d;
// after all triangles a sub-sample's bit is set when an odd number of surfaces lie in front of it.
// The rasteriser's fill rule gives one fragment per pixel centre where two triangles share an
// edge, so each crossing flips once.
flat in int vLayer;

uniform int uSlot;     // translucent slot of the object drawn
uniform int uSamples;  // 2N: sub-samples per column
uniform int uWords;    // 32-bit words per column

layout(r32ui, binding = 0) uniform coherent uimage2DArray uParity;

void main() {
  // Sub-sample k lies at depth (k + ½)/2N; it is behind the fragment when k ≥ ⌈2N d − ½⌉.
  float d = gl_FragCoord.z * float(uSamples);
  int first = clamp(int(ceil(d - 0.5)), 0, uSamples);
  ivec2 column = ivec2(gl_FragCoord.xy);
  for (int w = 0; w < uWords; ++w) {
    int lo = 32 * w;
    if (first >= lo + 32) continue;
    uint mask = first <= lo ? 0xFFFFFFFFu : (0xFFFFFFFFu << uint(first - lo));
    imageAtomicXor(uParity, ivec3(column, (uSlot * 3 + vLayer) * uWords + w), mask);
  }
}
