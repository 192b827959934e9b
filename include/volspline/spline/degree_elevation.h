#pragma once
// Degree elevation: the same geometry with a higher degree in one direction.
#include "volspline/spline/tensor_spline.h"

namespace volspline {

/// Raises the degree of `direction` by `times` (>= 0). Every distinct knot's multiplicity grows
/// by `times`, so the continuity is unchanged. Unclamped knot vectors are clamped first.
/// For rational splines the homogeneous form is elevated, which also removes isolated
/// weight-0 control points (Lasser 1994: "infinite control points can be eliminated by degree
/// elevation"). \throw InvalidInput if times < 0 or direction is not 0..D-1.
template <int D>
TensorSpline<D> elevate_degree(const TensorSpline<D>& spline, int direction, int times = 1);

}  // namespace volspline
