#version 450 core
// render.aa: the running weighted mean of a still's jittered camera frames (sss/still_average.h).
// History H_k = H_{k−1} + (w_k / W_k) (R_k − H_{k−1}), W_k = Σ_{j≤k} w_j, with R_k this frame's
// radiance and w_k its weight (the samples its translucency estimate holds); the mean is written
// back into the camera target, so the display, the PNG and the EXR all show it.
layout(local_size_x = 16, local_size_y = 16) in;

layout(rgba32f, binding = 0) uniform image2D uRadiance;  // this frame in, the mean out
layout(rgba32f, binding = 1) uniform image2D uHistory;
uniform float uShare;  // w_k / W_k: 1 on the first frame of a still

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(uRadiance)))) return;
  vec4 frame = imageLoad(uRadiance, p);
  vec4 mean = uShare >= 1.0 ? frame : imageLoad(uHistory, p);
  mean += uShare * (frame - mean);
  imageStore(uHistory, p, mean);
  imageStore(uRadiance, p, mean);
}
