// One entry of the sample pattern as the GPU stores it (std430; sss/peers/image_space.h's PatternRecord):
// index (slot · T² + set) · N + j.
struct IsPatternGpu {
  vec4 offsetWeight;  // xy: offset [mm] along x_o's tangent frame, z: weight [mm²]
  vec4 coverage;      // rgb: per-band coverage weight
};
