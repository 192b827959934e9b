#pragma once
// Isosurfaces of an attribute of a DMS spline volume by marching tetrahedra over its domain
// (Hua–He–Qin §6.2): the domain tetrahedra are upsampled (Fig. 13), vertices are placed on the
// spline itself by root finding along the sampling tetrahedra's edges (not by linear
// interpolation), mapped by the volume's geometry, and normals come from the analytic gradient.
//
// Upsampling, crack-free either way (docs/simplex-splines.md, "Isosurfaces"):
// - by default, locally: conforming longest-edge bisection (mesh/longest_edge_bisection.h) until
//   every edge is at most the target; large tetrahedra are refined, small ones left alone, and
//   the refined mesh is conforming, so neighbours share every sampled edge;
// - with `subdivisions` = k, uniformly: every domain tetrahedron cut into k³ by the edgewise
//   subdivision of its barycentric lattice, vertices in the order of their global indices, so two
//   tetrahedra sharing a face subdivide it alike (the same k everywhere).
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
  /// k > 0: every domain tetrahedron cut into k³ alike (uniform). 0: local longest-edge
  /// bisection to target_edge.
  int subdivisions = 0;
  /// The longest sampling edge (domain units); 0: the domain's bounding-box diagonal / 40.
  double target_edge = 0;
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
  /// k of the uniform lattice; 0 for local bisection.
  int subdivisions = 0;
  /// The tetrahedra marched (k³ per domain tetrahedron, or the bisected mesh's).
  long long sampled_tetrahedra = 0;
  /// Spline evaluations (samples and root-finding steps).
  long long evaluations = 0;
  /// The largest |g(x) − value| at a vertex, relative to the attribute's range over the samples.
  double largest_residual = 0;
};

/// \throw InvalidInput for an unknown attribute, a volume without attributes, a k outside 1..64,
/// a negative target edge or one so short that bisection would make over 4 million tetrahedra.
SimplexIsosurface simplex_isosurface(const DmsSplineVolume& volume, const SimplexIsosurfaceOptions& options = {});

}  // namespace volspline
