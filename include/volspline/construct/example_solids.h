#pragma once
// Example solids built in code, used by `volspline demo`, the docs and the tests.
#include "volspline/spline/tensor_spline.h"

namespace volspline {

/// A tricubic B-spline volume, 6 x 5 x 4 control points on clamped uniform knots: a
/// 4 x 1.5 x 1 slab bent upwards along u (z += 0.12 x^2), with a bulge on its top.
BSplineVolume bent_tricubic_volume();

/// A 1 x 1 x 3 column of degree (1, 1, 3) twisted by `turns` full turns about its axis: each of
/// the 4 layers of control points is the square rotated by a further turns * 360 / 3 degrees.
BSplineVolume twisted_volume(double turns = 0.25);

/// The exact thick half cylinder r in [inner, outer], angle in [0, pi], z in [0, height] as a
/// rational volume of degree (1, 2, 1): Lasser 1994, Theorem 2 with alpha = 180 degrees, whose
/// middle angular control points are points at infinity (weight 0, coordinates a direction).
/// \throw InvalidInput unless 0 <= inner < outer and height > 0.
BSplineVolume half_cylinder_shell(double inner = 1.0, double outer = 2.0, double height = 1.0);

}  // namespace volspline
