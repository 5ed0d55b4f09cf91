#version 450 core
// Pass 3: index map. The first vertex of each cell in the transform-feedback buffer (emission
// order) is stored at its cell; the cell's other vertices follow it (vertex_record.glsl), so the
// quad pass finds vertex = map[cell] + offset. Dispatched indirectly from the vertex counter. A cell
// whose vertices did not all fit in the buffer (overflow) is not written; the quad pass checks
// every entry it reads, since the map is not cleared between extractions.
layout(local_size_x = 64) in;

#include "dual_contouring/vertex_record.glsl"

layout(std430, binding = 0) readonly buffer Vertices { DcVertex vertices[]; };
layout(std430, binding = 1) readonly buffer VertexCounter { uint vertexCount; };
layout(r32i, binding = 0) uniform writeonly iimage3D uIndexMap;

uniform int uSamples;
uniform uint uCapacity;  // vertices the buffer holds; later ones were dropped (overflow)

void main() {
  uint i = gl_GlobalInvocationID.x;
  uint stored = min(vertexCount, uCapacity);
  if (i >= stored) return;
  uint bits = vertices[i].bits;
  if (isFaceVertex(bits) || ownPatch(bits) != 0 || i + uint(vertexTotal(bits)) > stored) return;
  int cell = vertices[i].cell, cells = uSamples - 1;
  imageStore(uIndexMap, ivec3(cell % cells, (cell / cells) % cells, cell / (cells * cells)), ivec4(int(i)));
}
