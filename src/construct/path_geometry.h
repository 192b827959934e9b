#pragma once
// Small measurements of a sweep path shared by the frame computations, the frame fit and the
// sweep itself (construct/sweep_frames.h, construct/frame_fitting.h, construct/sweep.h).
#include <array>
#include <string>

#include <Eigen/Core>

#include "volspline/spline/tensor_spline.h"

namespace volspline::detail {

/// \throw InvalidInput naming `what` unless dimension == 3.
void require_dimension(int dimension, const std::string& what);
/// The largest |coordinate| of the path's finite control points, at least 1.
double path_scale(const BSplineCurve& path);
/// The diagonal of the box of the path's finite control points (1 for a single point).
double length_scale(const BSplineCurve& path);
/// Speeds below this are a vanishing tangent: relative to the average speed over the domain.
double speed_floor(const BSplineCurve& path);
Eigen::Vector3d point_at(const BSplineCurve& curve, double t);
/// Position and the derivatives up to `order` (<= 2); higher entries zero.
std::array<Eigen::Vector3d, 3> derivatives_at(const BSplineCurve& curve, double t, int order);
/// The frame whose columns are the three frame curves at t.
Eigen::Matrix3d evaluate_frame(const std::array<BSplineCurve, 3>& curves, double t);

}  // namespace volspline::detail
