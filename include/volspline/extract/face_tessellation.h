#pragma once
// Triangle meshes of the six boundary faces of a trivariate solid: the parametric part of its
// boundary (Joy-Duchaineau 1999, Theorem 4.1; the Jacobian-zero part is analysis/).
#include <vector>

#include "volspline/core/knot_vector.h"
#include "volspline/mesh/triangle_mesh.h"
#include "volspline/spline/tensor_spline.h"

namespace volspline {

struct FaceTessellationOptions {
  /// Segments per parameter direction across the whole domain; every knot breakpoint is added
  /// to the samples as well, so creases at knots of high multiplicity stay sharp.
  int resolution = 24;
  /// Merge vertices that coincide in space (within 1e-10 of the box diagonal) and drop the
  /// triangles that collapse, so that solids with degenerate faces (a ball's poles, a solid
  /// cylinder's axis) still give a closed surface.
  bool weld_coincident = true;
};

/// Parameter samples along one direction: `resolution` equal segments of the domain merged with
/// the breakpoints, ascending, without repeats.
std::vector<double> face_samples(const KnotVector& knots, int resolution);

/// The six faces as one welded mesh (parts Part::UMin..WMax of mesh/parts.h: u=min, u=max,
/// v=min, v=max, w=min, w=max; per-vertex parameters). Vertices shared by two faces are one vertex: faces are sampled on
/// common parameter values and welded by parameter. Triangles are oriented so that the enclosed
/// volume is positive (outward normals, whatever the handedness of the parameterisation).
/// For a volume whose faces are not degenerate the result is closed: every edge is shared by
/// exactly two triangles. \throw InvalidInput if resolution < 1 or the control points are not
/// in R^3 (where() = "control_points").
TriangleMesh tessellate_faces(const BSplineVolume& volume, const FaceTessellationOptions& options = {});

}  // namespace volspline
