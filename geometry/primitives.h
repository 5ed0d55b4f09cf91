#pragma once
// Analytic shapes for receivers and tests, centred at the origin, with exact normals.
#include "geometry/triangle_mesh.h"

namespace tallow::geometry {

/// Unit-radius sphere as a UV grid of `rings` × `segments` (vertices exactly on the sphere).
TriangleMesh makeSphere(int rings, int segments);
/// Square in the xz plane, side 1, normal +y.
TriangleMesh makePlane();
/// Axis-aligned cube of side 1, flat-shaded (24 vertices).
TriangleMesh makeBox();

}  // namespace tallow::geometry
