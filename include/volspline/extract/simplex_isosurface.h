#pragma once
// Isosurfaces of an attribute of a DMS spline volume by marching tetrahedra over its domain
// (Hua–He–Qin §6.2): each domain tetrahedron is upsampled (Fig. 13) into k³ tetrahedra by the
// edgewise subdivision of its barycentric lattice, vertices are placed on the spline itself by
// root finding along the sub-tetrahedra's edges (not by linear interpolation), mapped by the
// volume's geometry, and normals come from the analytic gradient.
//
// Crack-free: the edgewise subdivision of a tetrahedron depends only on the order of its
// vertices, and restricted to a face it is the edgewise subdivision of that face; every domain
// tetrahedron orders its vertices by their global index, so two tetrahedra sharing a face
// subdivide it alike, and every tetrahedron the surface crosses uses the same k (a different k
// on the two sides of a face would leave cracks). Docs: docs/simplex-splines.md.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "volspline/mesh/triangle_mesh.h"
#include "volspline/simplex/dms_spline_volume.h"

namespace volspline {

struct SimplexIsosurfaceOptions {
  /// The attribute; empty: the first one.
  std::string attribute;
  double value = 0;
  /// k, the sub-tetrahedra per edge of each domain tetrahedron; 0: chosen so that the longest
  /// sub-edge is at most target_edge.
  int subdivisions = 0;
  /// 0: the domain's bounding-box diagonal / 40.
  double target_edge = 0;
  /// The largest automatic k.
  int max_subdivisions = 12;
  /// Root finding along edges (true) or the linear interpolation of marching tetrahedra (false).
  bool exact_vertices = true;
};

struct SimplexIsosurface {
  /// Part::AttributeIsosurface; positions s(x) (the volume's geometry), parameters x (the
  /// domain point). Triangles face the side where the attribute is larger.
  TriangleMesh mesh;
  /// Unit normals per vertex in the physical space: J^{-T} ∇g normalised (J = ds/dx), pointing
  /// towards larger values.
  std::vector<Eigen::Vector3d> normals;
  int subdivisions = 0;
  /// Spline evaluations (samples and root-finding steps).
  long long evaluations = 0;
  /// The largest |g(x) − value| at a vertex, relative to the attribute's range over the samples.
  double largest_residual = 0;
};

/// \throw InvalidInput for an unknown attribute, a volume without attributes, or a k outside
/// 1..64.
SimplexIsosurface simplex_isosurface(const DmsSplineVolume& volume, const SimplexIsosurfaceOptions& options = {});

}  // namespace volspline
