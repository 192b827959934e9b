#pragma once
// Piecewise polynomials on common breakpoints, one univariate Bernstein polynomial per span on
// its own local parameter [0, 1]: the form in which a sweep multiplies the homogeneous forms of
// its path and frame curves (construct/sweep.h), and turns the product back into a B-spline.
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "volspline/core/bernstein_tensor.h"
#include "volspline/core/knot_vector.h"
#include "volspline/spline/tensor_spline.h"

namespace volspline::detail {

/// pieces[s] lives on [breaks[s], breaks[s + 1]]; all pieces have one degree and one number of
/// components.
using PiecewiseBernstein = std::vector<BernsteinTensor<1>>;

/// The union of the curves' breakpoints, ascending, and at each the smallest continuity of the
/// curves there (C^(p - multiplicity); INT_MAX at the ends and where no curve has a knot).
std::pair<std::vector<double>, std::vector<int>> merged_breakpoints(const std::vector<const BSplineCurve*>& curves);

/// The homogeneous form of `curve` (Lasser 1994, eq. 4) on the merged breakpoints `breaks`
/// (which contain the curve's own): its Bézier pieces after inserting the missing breakpoints.
/// \throw Error if the extraction does not give one piece per span (a broken invariant).
PiecewiseBernstein homogeneous_pieces(const BSplineCurve& curve, const std::vector<double>& breaks);

/// The scalar constant 1 on `spans` spans.
PiecewiseBernstein constant_one(std::size_t spans);

/// Span by span: degree elevation to q, the product (a scalar times anything), components.
PiecewiseBernstein elevate(const PiecewiseBernstein& f, int q);
PiecewiseBernstein multiply(const PiecewiseBernstein& scalar, const PiecewiseBernstein& f);
PiecewiseBernstein components(const PiecewiseBernstein& f, int first, int count);

/// Equal as functions: the same Bernstein coefficients after elevation to a common degree, up to
/// 1e-13 of the largest coefficient.
bool same_function(const PiecewiseBernstein& a, const PiecewiseBernstein& b);

/// The B-spline of degree deg(f) with the given continuity at each breakpoint (C^smoothness[i]
/// at breaks[i]) that equals f; the rows of the matrix are its coefficients. They are blossoms
/// of the pieces at consecutive knots (de Boor-Fix: x_i = blossom of any piece in the support of
/// N_i at t_{i+1}, ..., t_{i+q}), which is exact because f really has that smoothness; no linear
/// system is solved.
std::pair<KnotVector, Eigen::MatrixXd> to_bspline(const PiecewiseBernstein& f, const std::vector<double>& breaks,
                                                  const std::vector<int>& smoothness);

}  // namespace volspline::detail
