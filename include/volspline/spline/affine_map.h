#pragma once
// Affine maps of the control points, and the bounding box they give.
#include <utility>

#include <Eigen/Core>

#include "volspline/spline/tensor_spline.h"

namespace volspline {

/// x -> A x + b applied to every control point (A: m x k, b: m), which maps the spline itself
/// the same way (affine invariance). Points at infinity (weight 0) are directions and get A only.
/// \throw InvalidInput if the sizes do not match the spline's dimension.
template <int D>
TensorSpline<D> transform_affine(const TensorSpline<D>& spline, const Eigen::MatrixXd& A, const Eigen::VectorXd& b);

/// An axis-aligned box containing the spline over its domain, from control points (convex
/// hull property). With subdivisions = 0 it is the box of the control net as given (unclamped
/// splines included: it may be loose). With subdivisions = k > 0 the spline is cut into its
/// Bézier pieces, each halved k times in every direction, and the box is that of all their
/// control nets: it converges quadratically to the true box. Weight-0 control points lie outside
/// the hull; pieces holding one are halved further until none is left (their new weights are
/// positive combinations of the old, Lasser 1994 after eq. 5), and with subdivisions = 0 degree
/// elevation removes them. Returns (min, max).
template <int D>
std::pair<Eigen::VectorXd, Eigen::VectorXd> bounding_box(const TensorSpline<D>& spline, int subdivisions = 0);

}  // namespace volspline
