#pragma once
// Bézier extraction and splitting: the same geometry cut into pieces.
#include <utility>
#include <vector>

#include "volspline/spline/tensor_spline.h"

namespace volspline {

/// Every nonempty knot cell as its own Bézier spline (single-span clamped knot vectors on the
/// cell's own parameter box), in cell order with the first direction fastest. Together the
/// pieces are exactly the input (knot insertion to full multiplicity).
template <int D>
std::vector<TensorSpline<D>> bezier_pieces(const TensorSpline<D>& spline);

/// The pieces on [min, t] and [t, max] of `direction`, each on its own sub-domain.
/// \throw InvalidInput unless min < t < max.
template <int D>
std::pair<TensorSpline<D>, TensorSpline<D>> split(const TensorSpline<D>& spline, int direction, double t);

}  // namespace volspline
