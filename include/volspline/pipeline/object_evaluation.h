#pragma once
// A model object evaluated as `volspline eval` prints it: one row per point, the point's
// coordinates and, with derivatives, its first partial derivatives — at parameters given one by
// one, or on a uniform grid over the whole domain whose last samples are the domain's ends
// exactly (no rounding off the domain).
#include <vector>

#include "volspline/io/model_file.h"

namespace volspline {

/// The k coordinates of `object` at `t` (one value per parameter), followed with `derivatives`
/// by its first partials, direction by direction (x_u y_u z_u x_v ...): k (D + 1) numbers.
/// \throw InvalidInput for a swept solid, or if t has not one value per parameter or lies outside the domain.
/// A simplex spline volume is evaluated as in evaluate_object_at_each.
std::vector<double> evaluate_object_at(const ModelObject& object, const std::vector<double>& t, bool derivatives = false);

/// evaluate_object_at for each of `points` (one spline set-up for all of them). For a simplex
/// spline volume a point is x, y, z in its domain and a row is the control vectors' entries
/// (x, y, z, then each attribute) followed with `derivatives` by their derivatives along x, then
/// y, then z; outside the domain every entry is 0 (the spline is zero there).
/// \throw InvalidInput as evaluate_object_at, located "points[i]".
std::vector<std::vector<double>> evaluate_object_at_each(const ModelObject& object, const std::vector<std::vector<double>>& points,
                                                         bool derivatives = false);

/// The rows of evaluate_object_at on the grid of counts[d] evenly spaced samples per direction d,
/// both ends included, the first direction fastest; evaluated by sum factorisation
/// (TensorSpline::evaluate_grid), not point by point.
/// For a simplex spline volume the grid spans the bounding box of its domain.
/// \throw InvalidInput for a swept solid, or if counts has not one entry per parameter or an entry is < 2.
std::vector<std::vector<double>> evaluate_object_on_grid(const ModelObject& object, const std::vector<int>& counts,
                                                         bool derivatives = false);

}  // namespace volspline
