#pragma once
// The exact derivative of a polynomial spline as a spline of one degree less.
#include "volspline/spline/tensor_spline.h"

namespace volspline {

/// The partial derivative in `direction` as a spline of degree p - 1 there, with control
/// points (Joy-Duchaineau 1999, §3)
///   Q_i = p / (t_{i+p+1} - t_{i+1}) (P_{i+1} - P_i),
/// on the knot vector without its first and last knot. A derivative of degree 0 is not a
/// spline we represent; \throw InvalidInput if the degree in `direction` is 1 or the spline is
/// rational (the derivative of a rational spline is rational of higher degree: use
/// evaluate_derivatives instead).
template <int D>
TensorSpline<D> derivative_spline(const TensorSpline<D>& spline, int direction);

}  // namespace volspline
