#pragma once
// Scalar fields carried by a spline's control points ("attributes" in model files): one value
// per control point, interpolated exactly like one more coordinate of the control points. For a
// rational spline that means the value joins the homogeneous point (w x, w a, w), so the field is
//   a(t) = sum_i N_i(t) w_i a_i / sum_i N_i(t) w_i
// with the weights of the geometry (Lasser 1994, eq. 4 applied to an extra coordinate).
#include <utility>
#include <vector>

#include "volspline/spline/tensor_spline.h"

namespace volspline {

/// The scalar spline (dimension 1) with the knots and weights of `geometry` and the control
/// values `values` (one per control point, u fastest).
/// \throw InvalidInput if the count is wrong or a value is not finite.
template <int D>
TensorSpline<D> attribute_spline(const TensorSpline<D>& geometry, const std::vector<double>& values);

/// `geometry` with the fields appended as extra coordinates: a spline of dimension
/// geometry.dimension() + fields.size() whose control point i is (x_i, fields[0][i], ...). Every
/// operation that is exact on the geometry (knot insertion, Bézier extraction) is then exact on
/// the fields too.
/// \throw InvalidInput if a field has the wrong count or a value that is not finite.
template <int D>
TensorSpline<D> append_coordinates(const TensorSpline<D>& geometry, const std::vector<std::vector<double>>& fields);

/// The inverse of append_coordinates: the first `dimension` coordinates as a spline (same knots
/// and weights) and each further coordinate as one field of control values.
/// \throw InvalidInput unless 1 <= dimension <= spline.dimension().
template <int D>
std::pair<TensorSpline<D>, std::vector<std::vector<double>>> split_coordinates(const TensorSpline<D>& spline, int dimension);

}  // namespace volspline
