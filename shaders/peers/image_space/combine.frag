#version 450 core
// image_space.combine: the second half of interleaved sampling (Keller and Heidrich 2001, cited by
// the image-space paper's §6.1). Every T×T window holds each of the T² sample sets once, so the
// mean of the scatter estimates over the window around a pixel uses T² N samples; neighbours on
// another object, turned away (normals more than ~25° apart) or off the pixel's tangent plane (a
// depth discontinuity: |(p_q − p)·n| > 0.5 |p_q − p|) are left out of the mean, so that light does
// not bleed across edges. The means are added (blending ONE, ONE) to the accumulation of the frames
// while nothing changes; alpha counts the frames.
uniform sampler2D uSum;       // image_space.scatter
uniform sampler2D uCoverage;
uniform sampler2D uPosition;  // image_space.gbuffer
uniform sampler2D uNormal;
uniform int uTile;

layout(location = 0) out vec4 oSum;
layout(location = 1) out vec4 oCoverage;

const float IS_COMBINE_MIN_NORMAL_COS = 0.9;
const float IS_COMBINE_MAX_PLANE_SLOPE = 0.5;

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  oSum = vec4(0.0);
  oCoverage = vec4(0.0);
  vec4 centre = texelFetch(uPosition, px, 0);
  int tag = int(centre.w + 0.5);
  if (tag == 0) return;
  vec3 n = texelFetch(uNormal, px, 0).xyz;
  ivec2 size = textureSize(uSum, 0);
  int start = -((uTile - 1) / 2);
  vec3 sum = vec3(0.0), coverage = vec3(0.0);
  float count = 0.0;
  for (int dy = start; dy < start + uTile; ++dy)
    for (int dx = start; dx < start + uTile; ++dx) {
      ivec2 q = px + ivec2(dx, dy);
      if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
      vec4 other = texelFetch(uPosition, q, 0);
      if (int(other.w + 0.5) != tag) continue;
      if (dot(texelFetch(uNormal, q, 0).xyz, n) < IS_COMBINE_MIN_NORMAL_COS) continue;
      vec3 d = other.xyz - centre.xyz;
      if (abs(dot(d, n)) > IS_COMBINE_MAX_PLANE_SLOPE * length(d)) continue;
      sum += texelFetch(uSum, q, 0).rgb;
      coverage += texelFetch(uCoverage, q, 0).rgb;
      count += 1.0;
    }
  oSum = vec4(sum / count, 1.0);
  oCoverage = vec4(coverage / count, 1.0);
}
