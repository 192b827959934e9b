#pragma once
// Cutting a tetrahedral domain along a material interface (Hua–He–Qin §4.2: sharp features need
// knots on the discontinuity surface and control vectors not shared across it). The interface is
// the zero set of a level function given at the points; each tetrahedron is cut by the zero set
// of its linear interpolant, so the pieces of two neighbours meet along the same polygons, and the
// points on the interface are duplicated, one copy per side: the result is a domain of parts that
// touch along the interface without sharing points (tetrahedron_parts), over which a simplex
// spline is one spline per side and jumps across the interface. Decisions: docs/fitting.md,
// "Sharp features".
#include <cstddef>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "volspline/mesh/tetrahedral_mesh.h"

namespace volspline {

struct InterfaceSplitOptions {
  /// Where an edge crosses the interface within this fraction of its length from an end, that
  /// end moves onto the interface (along its level normal) instead of the edge being cut, unless
  /// the move would turn a tetrahedron around it: no sliver pieces next to the interface (the
  /// snapping of isosurface stuffing). 0: no snapping.
  double snap = 0.25;
};

struct InterfaceSplit {
  /// The pieces, positively oriented; points on the interface appear once per side.
  TetrahedralMesh mesh;
  /// Per tetrahedron: 0 on the side where the level is negative, 1 where it is positive.
  std::vector<int> side;
  /// Tetrahedra that were cut, points moved onto the interface, and points on the interface
  /// (before duplication: snapped points and edge crossings).
  std::size_t cut_tetrahedra = 0, snapped_points = 0, interface_points = 0;
};

/// Cuts `mesh` (a valid, positively oriented tetrahedral mesh) along the zero set of the level
/// function whose values at its points are `level`; `normal` is, per point, the unit direction in
/// which the level grows (where a snapped point moves: p − level · normal). A cut tetrahedron's
/// side is a convex polytope (the tetrahedron and a half-space of the interpolant), split into
/// tetrahedra as a cone from its lowest-numbered corner after every quadrilateral face is split
/// through its lowest-numbered corner (points numbered: mesh points, then crossings in order of
/// their edges), so that neighbours' pieces share their faces. A tetrahedron with no point on the
/// negative (positive) side goes whole to side 1 (0); one whose points all have level 0, to 0.
/// \throw InvalidInput if the sizes differ from the mesh's points or a value is not finite.
InterfaceSplit split_at_interface(const TetrahedralMesh& mesh, std::span<const double> level, std::span<const Eigen::Vector3d> normal,
                                  const InterfaceSplitOptions& options = {});

}  // namespace volspline
