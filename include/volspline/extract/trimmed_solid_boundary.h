#pragma once
// The true boundary of a folded trivariate solid V([0,1]^3) (or a union of volumes): the faces
// and the surface J = 0 (Joy–Duchaineau 1999, extract/solid_boundary.h) are a superset of it,
// with parts inside V where the solid folds over itself; contouring the certified membership in
// V (SplineImage<3>) near that superset keeps only the boundary (extract/image_contouring.h),
// each vertex placed on its face or J = 0 by Newton on the sheet's equations
// (extract/sheet_line_crossing.h).
// docs/envelopes.md, "The true boundary of a folded solid".
#include <vector>

#include "volspline/extract/image_contouring.h"
#include "volspline/extract/jacobian_zero_surface.h"
#include "volspline/spline/tensor_spline.h"

namespace volspline {

struct TrimmedSolidBoundary {
  /// Parts and (u, v, w) from the superset sheet each vertex lies on.
  TriangleMesh mesh;
  /// The volume each vertex comes from.
  std::vector<int> volumes;
  SupersetTrimmingStats stats;
  /// Triangles of the superset (faces and J = 0 of every volume).
  std::size_t superset_triangles = 0;
};

/// The boundary of the union of the volumes' images. `superset` gives the faces' and J = 0's
/// tolerances; `contouring.cell_size` and `superset_error` are relative to the superset's
/// bounding-box diagonal. \throw InvalidInput for no volumes, a volume not in R^3, or options
/// out of range (as solid_boundary and contour_image_boundary).
TrimmedSolidBoundary trimmed_solid_boundary(const std::vector<BSplineVolume>& volumes, const BoundaryOptions& superset = {},
                                            const ImageContouringOptions& contouring = {});

}  // namespace volspline
