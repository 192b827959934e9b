#pragma once
// The conventions every part of volspline follows; other headers link here instead of
// repeating them.
//
// * Control points of a tensor-product spline with D parameters are stored with the first
//   parameter's index running fastest: for a volume, index = i + n_u * (j + n_v * k) for the
//   control point P_{i,j,k}. Coordinates of one point are contiguous (x, y, z, ...).
// * A parametric domain is a closed box [a_0, b_0] x ... x [a_{D-1}, b_{D-1}]; for a knot vector
//   of degree p with knots t_0..t_{m}, the domain is [t_p, t_{m-p}] (clamped or not).
// * Evaluation at a knot uses the span to the right of it, except at the upper end of the
//   domain, which belongs to the last nonempty span: splines are evaluated as right-continuous
//   functions, closed at the top.
// * Rational splines store Cartesian control points and weights w >= 0. Their homogeneous form
//   (Lasser 1994, eq. 4) has the coefficients (w x, w y, w z, w); a control point with w = 0 is a
//   point at infinity whose stored coordinates are a direction d, with homogeneous coefficient
//   (d, 0) (Lasser 1994, the paragraph after eq. 5).
// * Every triangle of a mesh carries a part number: which boundary face of a volume it lies on,
//   or the surface J = 0, an isoparametric surface, a slice, a box-spline blend's surface. The
//   numbers, their names and colours are one table: `Part` and `kParts` in mesh/parts.h.
