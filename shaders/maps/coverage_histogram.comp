#version 450 core
// sss.maps=auto's camera histograms (maps/coverage_counts.glsl) from the camera pass's per-pixel
// record (surface.frag's oCoverageBins: each bin + 1, 0 where Algorithm 1 did not shade): one count
// per visible pixel. Counting in the fragment shader instead counted every fragment that passed the
// depth test when drawn, hidden ones too (with culling off, the candle's far wall and the inside of
// its cup wherever they were drawn before the near wall: 5900 counts for 3200 visible pixels of the
// animated candle), and K followed what no one sees. Each workgroup sums into shared memory first,
// then adds its non-zero bins to the buffer.
#include "maps/coverage_count_buffer.glsl"

layout(local_size_x = 16, local_size_y = 16) in;

uniform usampler2D uCoverageBins;

shared uint localCounts[2 * COVERAGE_HISTOGRAM_SIZE];

void main() {
  uint i = gl_LocalInvocationIndex;
  if (i < uint(2 * COVERAGE_HISTOGRAM_SIZE)) localCounts[i] = 0u;
  barrier();
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (all(lessThan(p, textureSize(uCoverageBins, 0)))) {
    uvec2 bins = texelFetch(uCoverageBins, p, 0).xy;
    if (bins.x > 0u) {
      atomicAdd(localCounts[bins.x - 1u], 1u);
      atomicAdd(localCounts[uint(COVERAGE_HISTOGRAM_SIZE) + bins.y - 1u], 1u);
    }
  }
  barrier();
  if (i < uint(2 * COVERAGE_HISTOGRAM_SIZE) && localCounts[i] > 0u) {
    uint histogram = i < uint(COVERAGE_HISTOGRAM_SIZE) ? uint(COVERAGE_CAMERA) : uint(COVERAGE_CAMERA_FACING);
    uint bin = i % uint(COVERAGE_HISTOGRAM_SIZE);
    atomicAdd(coverageCounts[histogram * uint(COVERAGE_HISTOGRAM_SIZE) + bin], localCounts[i]);
  }
}
