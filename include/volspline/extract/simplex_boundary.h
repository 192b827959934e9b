#pragma once
// The boundary of a DMS spline solid: the image s(∂Ω) of the domain's boundary faces under the
// volume's geometry (Hua–He–Qin §3.3: the solid is s(Ω), and for an injective s its boundary is
// s(∂Ω)). The faces are sampled on the spline after the conforming longest-edge bisection of the
// domain (mesh/longest_edge_bisection.h) that the isosurfaces use, so neighbouring faces share
// their sampled edges and the surface is closed wherever ∂Ω is. Docs: docs/simplex-splines.md.
#include "volspline/mesh/triangle_mesh.h"
#include "volspline/simplex/dms_spline_volume.h"

namespace volspline {

struct SimplexBoundaryOptions {
  /// The longest sampling edge in the domain; 0: the domain's bounding-box diagonal / 40.
  double target_edge = 0;
};

/// Part::DomainBoundary triangles, oriented outward (as the domain's boundary faces; the image
/// keeps that orientation where the geometry's Jacobian is positive), positions s(x),
/// parameters x (the domain point).
/// \throw InvalidInput for a negative target edge or one so short that bisection would make over
/// 4 million tetrahedra.
TriangleMesh simplex_boundary_mesh(const DmsSplineVolume& volume, const SimplexBoundaryOptions& options = {});

}  // namespace volspline
