#version 450 core
// Pass 3: index map. Vertex i of the transform-feedback buffer (emission order) is stored at its
// cell, so the quad pass finds the shared vertices. Dispatched indirectly from the vertex counter.
layout(local_size_x = 64) in;

struct DcVertex { float px, py, pz, nx, ny, nz; int cell; };
layout(std430, binding = 0) readonly buffer Vertices { DcVertex vertices[]; };
layout(std430, binding = 1) readonly buffer VertexCounter { uint vertexCount; };
layout(r32i, binding = 0) uniform writeonly iimage3D uIndexMap;

uniform int uSamples;
uniform uint uCapacity;  // vertices the buffer holds; later ones were dropped (overflow)

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= min(vertexCount, uCapacity)) return;
  int cell = vertices[i].cell, cells = uSamples - 1;
  imageStore(uIndexMap, ivec3(cell % cells, (cell / cells) % cells, cell / (cells * cells)), ivec4(int(i)));
}
