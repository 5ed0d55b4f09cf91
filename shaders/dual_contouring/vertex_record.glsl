// A dual-contouring vertex as captured by pass 2 and read by passes 3 and 4 (std430, 32 bytes).
// `bits` packs, for the cell the vertex belongs to:
//   bits 0–23   the patch of each of its 12 edges (2 bits per edge, bits 2e and 2e + 1),
//   bits 24–25  the vertex's own patch,
//   bits 26–27  the cell's patch count − 1,
//   bits 28–30  bit k set when the cell owns the two face vertices of its upper face along axis k,
//   bit 31      set on a face vertex (not a patch vertex);
// see patches.glsl. A cell's vertices are consecutive: its patches in order, then two face vertices
// per set bit of 28–30, by axis, each pair ordered by slot.
struct DcVertex { float px, py, pz, nx, ny, nz; int cell; uint bits; };

int edgePatch(uint bits, int e) { return int((bits >> (2 * e)) & 3u); }
uint withPatch(uint bits, int pid, int count) { return bits | (uint(pid) << 24) | (uint(count - 1) << 26); }
int ownPatch(uint bits) { return int((bits >> 24) & 3u); }
int patchCount(uint bits) { return int((bits >> 26) & 3u) + 1; }
uint faceFlags(uint bits) { return (bits >> 28) & 7u; }
bool isFaceVertex(uint bits) { return (bits & 0x80000000u) != 0u; }
int vertexTotal(uint bits) { return patchCount(bits) + 2 * bitCount(faceFlags(bits)); }
// Offset of the face vertex (axis k, slot) from the cell's first vertex.
int faceVertexOffset(uint bits, int k, int slot) {
  return patchCount(bits) + 2 * bitCount(faceFlags(bits) & ((1u << k) - 1u)) + slot;
}
