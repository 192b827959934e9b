#pragma once
// The boundary of a trivariate solid (Joy–Duchaineau 1999, Theorem 4.1): the six face patches
// (extract/face_tessellation.h) plus the implicit surface J = 0 (extract/jacobian_zero_surface.h,
// whose options, statistics and result type this shares). docs/boundary.md.
#include "volspline/extract/jacobian_zero_surface.h"
#include "volspline/spline/tensor_spline.h"

namespace volspline {

/// The six faces plus the implicit surface, in one mesh (faces first). \throw InvalidInput as
/// jacobian_zero_surface.
SolidBoundary solid_boundary(const BSplineVolume& volume, const BoundaryOptions& options = {});

}  // namespace volspline
