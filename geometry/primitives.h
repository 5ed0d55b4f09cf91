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
/// A cup: a closed, outward-facing hollow cylinder about the +y axis, standing on y = 0 (its
/// anchor is the bottom centre, unlike the shapes above). Outer wall of radius `outerRadius` from
/// y = 0 to `height`; a cavity of radius `innerRadius` open at the top, from its floor at
/// y = `bottomThickness` up to `height`; an annulus closes the top of the wall, a disc the bottom.
/// Both circles are regular `segments`-gons with vertices on the circle (at angles 2πk/segments).
/// Walls are smooth-shaded (radial normals, pointing into the cavity on the inner wall), the three
/// caps flat; vertices are duplicated along the four rims so that each surface keeps its own
/// normals (welded by position the mesh is watertight: every edge in exactly two triangles).
/// Requires 0 < innerRadius < outerRadius, 0 < bottomThickness < height, segments ≥ 3.
TriangleMesh makeHollowCylinder(double innerRadius, double outerRadius, double height, double bottomThickness,
                                int segments);

}  // namespace tallow::geometry
