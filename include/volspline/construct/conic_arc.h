#pragma once
// Lasser's conic directrices (Lasser 1994, eq. 9 and Theorem 2): rational quadratic arcs whose
// type (ellipse, parabola, hyperbola) is set by one weight. Translation along one:
// translation_along_conic in construct/sweep.h.
#include <Eigen/Core>

#include "volspline/spline/tensor_spline.h"

namespace volspline {

/// Lasser 1994, eq. 9: the rational quadratic Bézier arc K(w) = sum_k s_k M_k K_0 B_k^2(w),
/// s_0 = s_2 = 1, with M_k the rotation of Theorem 2 about the axis through `axis_point` along
/// `axis_direction` (right-handed, angle in degrees, 0 < |angle| <= 180). The middle control
/// point is where the end tangents of the circular arc meet, with weight s2 cos(angle / 2):
/// a circle for s2 = 1, a parabola for s2 = 1 / cos(angle / 2) (all weights 1: polynomial),
/// a hyperbola for larger s2, an ellipse for smaller. At |angle| = 180 the middle point is at
/// infinity (weight 0) and the arc is half an ellipse (half a circle for s2 = 1).
/// \throw InvalidInput for a zero or non-finite axis, a start on the axis, an angle outside
/// that range, or s2 <= 0.
BSplineCurve conic_arc(Eigen::Vector3d start, double angle_deg, double s2, Eigen::Vector3d axis_point,
                       Eigen::Vector3d axis_direction);

}  // namespace volspline
