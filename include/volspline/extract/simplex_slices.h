#pragma once
// Planar slices through the domain of a DMS spline volume, coloured by an attribute
// (Hua–He–Qin Fig. 6d): the plane n·x = d cut through the upsampled lattice of every domain
// tetrahedron (extract/simplex_isosurface.h's crack-free edgewise subdivision), exact where it
// crosses the lattice's edges (the plane is linear), the vertices mapped by the volume's geometry
// and carrying the attribute evaluated there. The plane lies in the domain (material
// coordinates); with the identity geometry that is the same as in space.
#include <string>
#include <vector>

#include "volspline/mesh/plane.h"
#include "volspline/mesh/triangle_mesh.h"
#include "volspline/simplex/dms_spline_volume.h"

namespace volspline {

struct SimplexSliceOptions {
  /// The attribute the vertices carry; empty: the first, or none for a volume without attributes.
  std::string attribute;
  /// Sub-tetrahedra per domain tetrahedron edge (0: automatic, as for isosurfaces).
  int subdivisions = 0;
  double target_edge = 0;
  int max_subdivisions = 12;
};

struct SimplexSlice {
  /// Part::Slice; positions s(x), parameters x. Facing the plane's normal.
  TriangleMesh mesh;
  /// The attribute at each vertex (empty without attributes).
  std::vector<double> values;
  int subdivisions = 0;
};

/// \throw InvalidInput for an unknown attribute, a zero normal or a k outside 1..64.
SimplexSlice simplex_plane_slice(const DmsSplineVolume& volume, const Plane& plane, const SimplexSliceOptions& options = {});

}  // namespace volspline
