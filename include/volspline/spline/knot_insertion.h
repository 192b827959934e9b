#pragma once
// Knot insertion (Boehm) and refinement: the same geometry on a finer knot vector.
#include <vector>

#include "volspline/spline/tensor_spline.h"

namespace volspline {

/// Inserts t `times` times into the knot vector of `direction` (Boehm's algorithm on the
/// homogeneous coefficients). \throw InvalidInput if t is outside the domain or its
/// multiplicity would exceed degree + 1.
template <int D>
TensorSpline<D> insert_knot(const TensorSpline<D>& spline, int direction, double t, int times = 1);

/// Inserts every value of `knots` (in any order, repeats allowed) into `direction`.
template <int D>
TensorSpline<D> refine_knots(const TensorSpline<D>& spline, int direction, const std::vector<double>& knots);

/// The same geometry with clamped knot vectors in every direction (ends of multiplicity
/// degree + 1), dropping control points whose basis functions vanish on the domain.
template <int D>
TensorSpline<D> clamp(const TensorSpline<D>& spline);

}  // namespace volspline
