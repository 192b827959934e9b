#pragma once
// The Delaunay tetrahedralisation of a point set (Hua–He–Qin §4.1, §5.2: the domain of a
// simplex spline built from scattered points). docs/tetrahedral-domains.md.
#include <span>

#include <Eigen/Core>

#include "volspline/mesh/tetrahedral_mesh.h"

namespace volspline {

/// CGAL's 3-D Delaunay triangulation of the points (finite cells only), point indices preserved.
/// The tetrahedra are positively oriented and cover the convex hull; where points are
/// cospherical the choice among the Delaunay tetrahedralisations is CGAL's symbolic
/// perturbation, which depends on the coordinates only, so the result is deterministic.
/// \throw InvalidInput for fewer than 4 points or all of them coplanar (located at `points`), a
/// duplicate (at `points[j]`, naming the earlier `points[i]`) or a coordinate that is not finite
/// (at `points[i]`).
TetrahedralMesh delaunay_tetrahedralization(std::span<const Eigen::Vector3d> points);

}  // namespace volspline
