#pragma once
// Restriction to an iso-parameter: a volume's face is a surface, a surface's edge a curve.
#include "volspline/spline/tensor_spline.h"

namespace volspline {

/// The (D-1)-variate spline t_direction = value, keeping the other directions in order.
/// Exact: the control points are the basis combination of the rows across `direction`
/// (homogeneous, so rational splines stay exact). \throw InvalidInput if value is outside the
/// domain.
template <int D>
TensorSpline<D - 1> restrict_to_iso(const TensorSpline<D>& spline, int direction, double value);

}  // namespace volspline
