#version 450 core
// render.aa: a still's jittered camera frames averaged (sss/still_average.h). Frame k has radiance
// R_k and translucent part T_k with h_k = 1 where a translucent surface is drawn (0 elsewhere), and
// its translucent estimate's weight w_k (the samples it holds). The picture after N frames is
//   mean_k(R_k − h_k T_k) + mean_k(h_k) · Σ_k w_k h_k T_k / Σ_k w_k h_k,
// the plain mean where the estimate is not drawn, and where every frame draws it (h_k = 1) the
// plain mean of the rest plus the estimate's weighted mean. The means run as M_k = M_{k−1} +
// (X_k − M_{k−1}) / k; the picture is written back into the camera target, so the display, the PNG
// and the EXR all show it.
layout(local_size_x = 16, local_size_y = 16) in;

layout(rgba32f, binding = 0) uniform image2D uRadiance;         // this frame in, the still out
layout(rgba32f, binding = 1) readonly uniform image2D uTranslucent;
layout(rgba32f, binding = 2) uniform image2D uRest;             // mean of R − h T
layout(rgba32f, binding = 3) uniform image2D uTranslucentSum;   // Σ w h T, Σ w h
layout(r32f, binding = 4) uniform image2D uTranslucentShare;    // mean of h
uniform int uFirst;     // 1: the still starts at this frame
uniform float uShare;   // 1 / N
uniform float uWeight;  // w_k > 0

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(uRadiance)))) return;
  vec4 frame = imageLoad(uRadiance, p);
  vec4 translucent = imageLoad(uTranslucent, p);
  float h = translucent.a > 0.5 ? 1.0 : 0.0;
  vec4 rest = frame - vec4(h * translucent.rgb, 0.0);
  vec4 sum = vec4(uWeight * h * translucent.rgb, uWeight * h);
  float share = h;
  if (uFirst == 0) {
    vec4 restMean = imageLoad(uRest, p);
    rest = restMean + uShare * (rest - restMean);
    sum += imageLoad(uTranslucentSum, p);
    float shareMean = imageLoad(uTranslucentShare, p).r;
    share = shareMean + uShare * (share - shareMean);
  }
  imageStore(uRest, p, rest);
  imageStore(uTranslucentSum, p, sum);
  imageStore(uTranslucentShare, p, vec4(share));
  vec3 estimate = sum.a > 0.0 ? sum.rgb / sum.a : vec3(0.0);
  imageStore(uRadiance, p, rest + vec4(share * estimate, 0.0));
}
