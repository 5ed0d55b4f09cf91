// The storage buffer of sss.maps=auto's coverage counts (maps/coverage_counts.glsl's layout),
// bound at binding 9 only while a frame counts (sss/maps/map_coverage_probe.h).
#include "maps/coverage_counts.glsl"
layout(std430, binding = 9) buffer MapCoverageCounts { uint coverageCounts[]; };

/// The bin of a point whose histogram-completing map is `map` (−1: none).
int coverageBin(int map) { return map >= 0 ? min(map, COVERAGE_MAX_MAPS - 1) : COVERAGE_MAX_MAPS; }

void countInto(int histogram, int map) {
  atomicAdd(coverageCounts[histogram * COVERAGE_HISTOGRAM_SIZE + coverageBin(map)], 1u);
}
