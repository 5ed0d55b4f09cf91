#pragma once
// CPU reference mesher: OpenVDB's volumeToMesh (isovalue 0, adaptivity 0) on a sampled lattice.
// OpenVDB stays inside cpu_mesher.cpp; this header is all the rest of the code sees.
#include "geometry/grid_sampler.h"
#include "geometry/scalar_field.h"
#include "geometry/triangle_mesh.h"

namespace tallow::geometry {

/// Triangles of the zero level set of `lattice`, in world units, counter-clockwise seen from
/// outside (value > 0); quads are split along their shorter diagonal. Normals are the normalised
/// gradient of `field` at each vertex (pass the field that was sampled). A surface that leaves
/// the lattice is cut open at its boundary.
TriangleMesh meshOnCpu(const SampledLattice& lattice, const ScalarField& field);
/// Samples `field` on n³ points over its bounds, then meshes it as above.
TriangleMesh meshOnCpu(const ScalarField& field, int n);

}  // namespace tallow::geometry
