#version 450 core
// Pass 2 (surface nets, Gibson 1998): one vertex per sign-changing cell at the mean of its edge
// crossings, normal = normalised field gradient by central differences on the texture. Captured by
// transform feedback as (position, normal, cell); the counter also builds the indirect dispatch of
// the index-map pass (one work group per 64 vertices).
#include "dual_contouring/lattice.glsl"

layout(points) in;
layout(points, max_vertices = 1) out;

flat in ivec3 vCell[];
out vec3 tfPosition;
out vec3 tfNormal;
flat out int tfCell;

// {count, groupsX, groupsY, groupsZ}
layout(std430, binding = 1) buffer VertexCounter { uint vertexCount; uint groupsX; uint groupsY; uint groupsZ; };

const ivec2 kEdges[12] = ivec2[12](ivec2(0, 1), ivec2(2, 3), ivec2(4, 5), ivec2(6, 7),   // along x
                                   ivec2(0, 2), ivec2(1, 3), ivec2(4, 6), ivec2(5, 7),   // along y
                                   ivec2(0, 4), ivec2(1, 5), ivec2(2, 6), ivec2(3, 7));  // along z

vec3 corner(int i) { return vec3(i & 1, (i >> 1) & 1, (i >> 2) & 1); }

float sampleLinear(vec3 s) { return texture(uField, (s + 0.5) / float(uSamples)).r; }

void main() {
  ivec3 c = vCell[0];
  if (c.x < 0) return;
  float v[8];
  int insideCount = 0;
  for (int i = 0; i < 8; ++i) {
    v[i] = fieldAt(c + ivec3(corner(i)));
    insideCount += isInside(v[i]) ? 1 : 0;
  }
  if (insideCount == 0 || insideCount == 8) return;

  vec3 sum = vec3(0.0);
  float crossings = 0.0;
  for (int e = 0; e < 12; ++e) {
    int a = kEdges[e].x, b = kEdges[e].y;
    if (isInside(v[a]) == isInside(v[b])) continue;
    float t = clamp(v[a] / (v[a] - v[b]), 0.0, 1.0);
    sum += mix(corner(a), corner(b), t);
    crossings += 1.0;
  }
  vec3 s = vec3(c) + sum / crossings;  // lattice coordinates
  const float h = 0.5;                 // half-cell central differences (trilinear texture)
  vec3 g = vec3(sampleLinear(s + vec3(h, 0, 0)) - sampleLinear(s - vec3(h, 0, 0)),
                sampleLinear(s + vec3(0, h, 0)) - sampleLinear(s - vec3(0, h, 0)),
                sampleLinear(s + vec3(0, 0, h)) - sampleLinear(s - vec3(0, 0, h)));
  float len = length(g);

  uint index = atomicAdd(vertexCount, 1u);
  if (index % 64u == 0u) atomicAdd(groupsX, 1u);
  tfPosition = uOrigin + uCellSize * s;
  tfNormal = len > 0.0 ? g / len : vec3(0.0, 1.0, 0.0);
  tfCell = cellIndex(c);
  EmitVertex();
  EndPrimitive();
}
