#pragma once
// The range of coordinates a model may hold (issue 16; docs/model-format.md, "Range of
// coordinates"). Every reader (JSON, G+Smo, IRIT, VTU) checks a model with
// check_coordinate_range before handing it out, and every writer before writing, so no command
// sees coordinates whose powers overflow or underflow: the Jacobian determinant is a cubic in the
// size of a solid and the moments of inertia a quintic, so a solid of size 1e200 or 1e-200 gave
// infinities, zeros and NaNs deep inside (weld tolerances, parameters, colours) instead of an
// answer. The rule itself is core/coordinate_range.h, shared with every other reader. Within the range, every command works (far from the origin included: local_origin).
#include "volspline/core/coordinate_range.h"
#include "volspline/io/model_file.h"

namespace volspline {

/// The largest magnitude of a coordinate (of a control point, or of the direction of a point at
/// infinity): 2^200, about 1.6e60; a quintic in it stays below the largest double.
inline constexpr double kMaxModelCoordinate = kMaxCoordinate;
/// The least extent of an object whose control points are not all one point (the largest edge
/// of their bounding box): 2^-200, about 6.2e-61; a cubic in it stays a normal double.
inline constexpr double kMinModelExtent = kMinExtent;

/// \throw InvalidInput located at the object and the offending number
/// ("objects[2].control_points[5][1]"), saying what the range is and why, for a coordinate
/// beyond kMaxModelCoordinate or an object smaller than kMinModelExtent. Covers tensor-product
/// splines of every dimension, swept solids (generator, path, frame curves) and simplex spline
/// volumes (domain points, control vectors' coordinates).
void check_coordinate_range(const Model& model);

}  // namespace volspline
