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

/// An axis-aligned box containing the spline over its whole domain: the box of the control
/// points (convex hull property). Weight-0 control points are not in the hull; they are first
/// removed by degree elevation, whose new weights are positive combinations of neighbouring
/// ones (Lasser 1994, after eq. 5). With `subdivisions` > 0 every knot span is first halved
/// that many times by knot insertion; the control net then approaches the spline
/// quadratically, so the box tightens to the true one. Returns (min, max).
template <int D>
std::pair<Eigen::VectorXd, Eigen::VectorXd> bounding_box(const TensorSpline<D>& spline, int subdivisions = 0);

}  // namespace volspline
