#pragma once
// Volumes of revolution (spin volumes): Lasser 1994, Theorem 2 (eq. 8), about any axis.
#include <Eigen/Core>

#include "volspline/spline/tensor_spline.h"

namespace volspline {

/// The exact volume swept by rotating `profile` (a surface in R^3) about the axis through
/// `axis_point` with direction `axis_direction` by `angle_deg` degrees, counter-clockwise seen
/// from the tip of the direction (right-hand rule). u and v are the profile's; w in [0, 1] is the
/// angular direction, degree 2, made of n = ceil(angle / 90) equal arcs joined at double knots
/// k / n (C0 in the parameter, G1 in space). Every arc is Theorem 2 with alpha = angle / n <= 90
/// degrees, so all new weights are >= cos 45 deg times the profile's. Rational profiles are
/// handled in homogeneous form (V_ijk = M_k F_ij), so points at infinity of the profile stay
/// exact. V(u, v, 0) = F(u, v) bit for bit; for 360 degrees the last control points are copies
/// of the first, so the faces w = 0 and w = 1 coincide up to evaluation rounding.
/// \throw InvalidInput (where() "profile") if the profile is not in R^3, ("axis_direction") if
/// the direction is zero or not finite, ("axis_point") if not finite, ("angle") unless
/// 0 < angle_deg <= 360.
BSplineVolume revolve(const BSplineSurface& profile, const Eigen::Vector3d& axis_point, const Eigen::Vector3d& axis_direction,
                      double angle_deg);

/// Lasser's single segment (Theorem 2 as stated): degree 2 in w on a single Bézier span [0, 1],
/// middle control points M_1 F_ij with the weights multiplied by cos(alpha / 2). At alpha =
/// 180 degrees they are points at infinity (weight 0), as in Fig. 2 and 3; a profile point on
/// the axis then gives the zero homogeneous coefficient, which is harmless because the end
/// weights carry the denominator.
/// \throw InvalidInput as revolve, with ("angle") unless 0 < angle_deg <= 180.
BSplineVolume revolve_single_segment(const BSplineSurface& profile, const Eigen::Vector3d& axis_point,
                                     const Eigen::Vector3d& axis_direction, double angle_deg);

}  // namespace volspline
