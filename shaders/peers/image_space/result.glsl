// B(x_o) of the image-space method for the surface pass: the accumulated combined estimates of
// image_space.combine (Σ over F frames of B and of the coverage; alpha: F) at the pixel.
uniform sampler2D uImageSpaceSum;
uniform sampler2D uImageSpaceCoverage;
uniform int uImageSpaceRenormalize;  // image_space.renormalize

// renormalize off: the mean over the frames, an unbiased estimate of ∫ R_d E dA over the part of
// the disc that the camera sees as x_o's surface. On: divided per band by the sampled share of
// R_d's mass on that part (the coverage), i.e. the missing part is assumed lit like the part seen
// (the paper's §6.2 divides by the count of valid samples, the same for one band and no uniform samples).
vec3 imageSpaceRadiosity(ivec2 pixel) {
  vec4 sum = texelFetch(uImageSpaceSum, pixel, 0);
  if (!(sum.a > 0.0)) return vec3(0.0);
  if (uImageSpaceRenormalize == 0) return sum.rgb / sum.a;
  vec3 coverage = texelFetch(uImageSpaceCoverage, pixel, 0).rgb;
  return vec3(coverage.r > 0.0 ? sum.r / coverage.r : 0.0, coverage.g > 0.0 ? sum.g / coverage.g : 0.0,
              coverage.b > 0.0 ? sum.b / coverage.b : 0.0);
}
