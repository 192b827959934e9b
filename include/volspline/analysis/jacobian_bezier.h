#pragma once
// The Jacobian determinant of a Bézier cell, exactly, in Bernstein form (docs/jacobian.md).
//
// Joy–Duchaineau §4 (Theorem 4.1) put the implicit part of a solid's boundary where
// J = p_u . (p_v x p_w) vanishes, and bound J with cones (§5). For a polynomial cell of degree
// (p, q, r), J is itself a polynomial of degree (3p-1, 3q-1, 3r-1); its Bernstein coefficients
// come from products in the Bernstein basis, and their convex hull bounds J on the cell far more
// tightly than cones do, converging quadratically under subdivision. For a rational cell with
// homogeneous point P = (w, wx, wy, wz), J = det[P; P_u; P_v; P_w] / w^4, so the sign of J is
// the sign of that 4 x 4 determinant, a polynomial of degree (4p-1, 4q-1, 4r-1).
//
// Every coefficient comes with a proven floating-point error bound, so that a sign decided from
// coefficient +- bound is never wrong (the derivation is in docs/jacobian.md).
#include "volspline/core/bernstein_tensor.h"
#include "volspline/spline/tensor_spline.h"

namespace volspline {

struct JacobianBernstein {
  /// Polynomial cell: the coefficients of J. Rational cell: those of w^4 J = det[P; P_u; P_v;
  /// P_w] (columns w, wx, wy, wz). Local parameters [0, 1]^3 over the cell; the derivatives are
  /// taken with respect to the global parameters, so the polynomial equals J (or w^4 J) at the
  /// corresponding global point.
  BernsteinTensor<3> coefficients;
  /// |computed coefficient - exact coefficient| <= error_bound for every coefficient, where
  /// "exact" is the cell whose control points are within the `input_error` given of the ones
  /// stored.
  double error_bound = 0;
  /// True for a rational cell: coefficients are those of w^4 J and `weights` holds w.
  bool homogeneous = false;
  /// Bernstein form of the weight function w (degree (p, q, r)); empty for a polynomial cell.
  BernsteinTensor<3> weights;
};

/// Bernstein coefficients of J over a single Bézier cell of a volume in R^3 (every knot vector a
/// single clamped span, e.g. from bezier_pieces). `input_error` bounds the absolute error of the
/// stored homogeneous coefficients (0 for a Bézier volume given by its control points; see
/// extraction_error_bound for pieces of a B-spline volume).
/// \throw InvalidInput if the volume is not a single Bézier cell in R^3.
JacobianBernstein jacobian_bezier_coefficients(const BSplineVolume& cell, double input_error = 0);

/// A bound on the absolute error of the homogeneous control points of every piece
/// bezier_pieces(volume) makes: each inserted knot forms convex combinations, which do not grow
/// earlier errors and add a few roundings of the largest coefficient.
double extraction_error_bound(const BSplineVolume& volume);

}  // namespace volspline
