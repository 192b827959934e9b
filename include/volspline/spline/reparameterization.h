#pragma once
// Affine reparameterisation: the same geometry over another parameter interval.
#include "volspline/spline/tensor_spline.h"

namespace volspline {

/// The spline with the knots of `direction` mapped affinely so that its domain becomes [a, b];
/// control points are unchanged (B-spline bases are invariant under affine knot maps).
/// \throw InvalidInput unless a < b and both are finite.
template <int D>
TensorSpline<D> reparameterize(const TensorSpline<D>& spline, int direction, double a, double b);

/// Every direction mapped to [0, 1] (the domain of a Bézier object in model files).
template <int D>
TensorSpline<D> reparameterize_to_unit_box(const TensorSpline<D>& spline);

}  // namespace volspline
