// A melting mesh at time t as a shader storage buffer and uniforms (GLSL only): the static NanoVDB
// grids (geometry::MeltGrids, uploaded once per preset load by geometry::GpuMeltField) read by
// PNanoVDB's GLSL port, and the melt's per-t scalars (geometry::MeltState), read by the lattice fill
// (fields/mesh_melt_lattice.comp) through fields/melt.glsl.
#define PNANOVDB_GLSL
// PNanoVDB's GLSL buffer functions read this array (its name is PNanoVDB's).
layout(std430, binding = 0) readonly buffer MeltGridBuffer { uint pnanovdb_buf_data[]; };
// Embedded at build time from libnanovdb-dev's header (cmake/EmbedShaders.cmake), not copied here.
#include "nanovdb/PNanoVDB.h"
#include "fields/melt.glsl"

uniform vec3 uMeltAnchor;        // MeltShape::anchor
uniform float uMeltHeightScale;  // s
uniform float uMeltInvVoxel;
uniform int uMeltGridA;          // byte addresses (< 2³¹, the buffer's size is checked on upload)
uniform int uMeltGridB;
uniform float uMeltBlend;
uniform float uMeltPuddleRadius;
uniform float uMeltPuddleHeight;
uniform float uMeltJoinRadius;
uniform vec3 uMeltBoxLo;
uniform vec3 uMeltBoxHi;
uniform float uMeltBackground;

float meltValueAt(vec3 p) {
  MeltShape m;
  m.anchor = uMeltAnchor;
  m.heightScale = uMeltHeightScale;
  m.invVoxel = uMeltInvVoxel;
  m.gridA = uint(uMeltGridA);
  m.gridB = uint(uMeltGridB);
  m.blend = uMeltBlend;
  m.puddleRadius = uMeltPuddleRadius;
  m.puddleHeight = uMeltPuddleHeight;
  m.joinRadius = uMeltJoinRadius;
  m.boxLo = uMeltBoxLo;
  m.boxHi = uMeltBoxHi;
  m.background = uMeltBackground;
  pnanovdb_buf_t buf;
  buf.unused = 0u;
  return meltFieldValue(buf, p, m);
}
