#pragma once
// Planar slices through the domain of a DMS spline volume, coloured by an attribute
// (Hua–He–Qin Fig. 6d): the plane n·x = d cut through the sampling tetrahedra of the domain (the
// same crack-free upsampling as isosurfaces, extract/simplex_isosurface.h: local longest-edge
// bisection by default, or k³ alike), exact where it crosses their edges (the plane is linear), the vertices mapped by the volume's geometry
// and carrying the attribute evaluated there. The plane lies in the domain (material
// coordinates); with the identity geometry that is the same as in space.
#include <span>
#include <string>
#include <vector>

#include "volspline/mesh/plane.h"
#include "volspline/mesh/triangle_mesh.h"
#include "volspline/simplex/dms_spline_volume.h"

namespace volspline {

struct SimplexSliceOptions {
  /// The attribute the vertices carry; empty: the first, or none for a volume without attributes.
  std::string attribute;
  /// k > 0: every domain tetrahedron cut into k³ alike (uniform). 0: local longest-edge
  /// bisection to target_edge.
  int subdivisions = 0;
  /// The longest sampling edge (domain units); 0: the domain's bounding-box diagonal / 40.
  double target_edge = 0;
};

struct SimplexSlice {
  /// Part::Slice; positions s(x), parameters x. Facing the plane's normal.
  TriangleMesh mesh;
  /// The attribute at each vertex (empty without attributes).
  std::vector<double> values;
  /// k of the uniform lattice; 0 for local bisection.
  int subdivisions = 0;
  /// The sampling tetrahedra the plane was cut through.
  long long sampled_tetrahedra = 0;
};

/// \throw InvalidInput for an unknown attribute, a zero normal, a k outside 0..64 or a target
/// edge that is negative or so short that bisection would make over 4 million tetrahedra.
SimplexSlice simplex_plane_slice(const DmsSplineVolume& volume, const Plane& plane, const SimplexSliceOptions& options = {});

/// Several planes through one sampling of the domain (bisected once).
std::vector<SimplexSlice> simplex_plane_slices(const DmsSplineVolume& volume, std::span<const Plane> planes, const SimplexSliceOptions& options = {});

}  // namespace volspline
