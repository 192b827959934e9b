#pragma once
// Solving s(p) = x for p in the closed parameter box of a spline map s : R^D -> R^3 (D = 3, or
// D = 4 with one more unknown than equations), when the Jacobian may be singular: damped
// least-squares (Levenberg–Marquardt) steps, whose limit for vanishing damping is the
// minimum-norm Gauss–Newton step J^+ r, projected onto the domain with the coordinates held
// at a bound that the descent direction pushes outwards. Where no solution exists it ends at a
// local minimum of |s(p) - x| over the domain: for x just outside the image, the closest point,
// whose residual direction is the outward normal there. Used by SplineImage
// (analysis/point_in_image.h); docs/envelopes.md, "Membership in the image of a spline map".
#include <array>

#include <Eigen/Core>

#include "volspline/spline/tensor_spline.h"

namespace volspline::detail {

template <int D>
struct DomainNewtonResult {
  std::array<double, D> parameter{};
  /// s(parameter) and |s(parameter) - x|.
  Eigen::Vector3d value = Eigen::Vector3d::Zero();
  double residual = 0;
  bool converged = false;
  /// The end point is a first-order minimum over the domain: the free part of J^T r is below
  /// 1e-6 of |J| |r|. False for a stall where |s - x| has a kink (a C0 knot) or the budget ran
  /// out; its residual direction is then no normal of the image.
  bool stationary = false;
};

/// From `start` (clamped into the domain), at most `max_evaluations` evaluations of s and its
/// first derivatives; converged when the residual is <= tolerance. The result is the best point
/// reached whether it converged or not. \throw InvalidInput unless s maps into R^3.
template <int D>
DomainNewtonResult<D> newton_in_domain(const TensorSpline<D>& s, const Eigen::Vector3d& x, const std::array<double, D>& start,
                                       double tolerance, int max_evaluations = 60);

}  // namespace volspline::detail
