#pragma once
// Cutting meshes by planes, for cutaway views: the faces of a solid with a wedge removed show
// its slices in place (Lasser 1994 Figs. 11, 13).
#include <vector>

#include "volspline/mesh/plane.h"
#include "volspline/mesh/triangle_mesh.h"

namespace volspline {

/// The part of `mesh` outside the convex region where normal_i·x > offset_i for every plane i
/// (one plane: its positive side; three coordinate planes: an octant). Triangles crossing a
/// plane are cut there: new vertices are placed on the plane by linear interpolation along the
/// edge (position and parameters) and shared by the triangles on both sides of the edge, so a
/// crack-free mesh stays crack-free. Unused vertices are dropped.
/// \throw InvalidInput for a malformed mesh or a plane with a zero or non-finite normal.
TriangleMesh remove_convex_region(const TriangleMesh& mesh, const std::vector<Plane>& planes);

/// The part of `mesh` inside that convex region (the complement of remove_convex_region).
TriangleMesh keep_convex_region(const TriangleMesh& mesh, const std::vector<Plane>& planes);

}  // namespace volspline
