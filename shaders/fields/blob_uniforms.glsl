// The blob at time t as uniforms (GLSL only): set by geometry::GpuBlobField from a BlobField, read
// by the lattice fill (fields/blob_lattice.comp) and the vertex normals (dual_contouring/
// vertices.geom with DC_BLOB_NORMALS) through fields/blob.glsl.
#include "fields/blob.glsl"

uniform vec3 uBlobCentres[BLOB_COUNT];  // pᵢ(t), unscaled units
uniform float uBlobSigma;               // σ, 1/unit²
uniform float uBlobIso;                 // the surface is Φ_t = iso
uniform float uBlobScale;               // metres per unscaled unit

float blobValueAt(vec3 p) { return blobFieldValue(p, uBlobCentres, uBlobSigma, uBlobIso, uBlobScale); }
vec3 blobGradientAt(vec3 p) { return blobFieldGradient(p, uBlobCentres, uBlobSigma, uBlobScale); }
