#pragma once
// The example solids of Joy-Duchaineau 1999, §8 (Figs. 10, 11 and 13), as reproducible
// constructions. The paper does not print its control points; the ones chosen here are
// documented below and in docs/sweeps.md, and are built so that the properties the paper states
// hold exactly.
//
// All three start from one bicubic Bézier patch F(u, v) with control points
//   P_ij = (i - 1.5,  y_j,  z_ij),  i, j = 0..3,
//   y_j = (-0.75, 0.75, 0.75, 0.375),
//   z_ij (rows j = 0..3, columns i = 0..3):
//     0.0  0.2  0.2  0.0
//     0.3  0.8  0.8  0.3
//     0.9  1.4  1.4  0.9
//     1.2  1.4  1.4  1.2
// so x = 3u - 1.5 is linear in u and y(v) depends on v only, with
//   y'(v) = 3 (1.5 (1 - v)^2 - 0.375 v^2) = 1.125 (2 - 3v)(2 - v),
// which changes sign at v = 2/3: seen along z the patch folds over itself along v = 2/3. (The
// end rows are at different y, so the faces v = 0 and v = 1 are not coplanar.)
#include <array>

#include <Eigen/Core>

#include "volspline/spline/tensor_spline.h"

namespace volspline {

/// The bicubic Bézier patch above (degree (3, 3), 4 x 4 control points).
BSplineSurface paper_example_patch();

/// Fig. 10: the patch swept along the straight line from the origin to d = (0, 0, 2),
/// V(u, v, w) = F(u, v) + w d, degree (3, 3, 1). Its Jacobian determinant is
/// det(F_u, F_v, d) = 3 y'(v) * 2 = 6.75 (2 - 3v)(2 - v): independent of u and w (the paper's
/// D_u = D_w = 0) and zero exactly on the plane v = 2/3, changing sign across it.
BSplineVolume swept_patch();

/// The four sections of twisted_loft: S_m = Rz(35 m / 3 degrees) F + (m / 3) d, m = 0..3, with
/// Rz the rotation about the z axis (the sweep direction through the origin).
std::array<BSplineSurface, 4> twisted_loft_sections();

/// Fig. 11: the patch rotated by 35 degrees about the sweep direction while swept along d,
/// sampled at four positions (twisted_loft_sections) and lofted by the cubic Bézier in w that
/// interpolates them at w = 0, 1/3, 2/3, 1. Degree (3, 3, 3).
BSplineVolume twisted_loft();

/// The path of curved_loft: the cubic B-spline with knots (0, 0, 0, 0, 0.5, 1, 1, 1, 1) and
/// control points (0, 0, 0), (0, 0, 1.5), (0.5, 0.8, 3.0), (2.5, 1.2, 4.0), (4.5, 0.8, 4.0).
BSplineCurve curved_loft_path();

/// The five sections of curved_loft: the patch carried rigidly along curved_loft_path by its
/// rotation-minimising frame, S_m = c(t_m) + R(t_m) R(0)^T (F - c(0)), t_m = m / 4.
std::array<BSplineSurface, 5> curved_loft_sections();

/// Fig. 13: the five sections lofted by the cubic B-spline in w with knots
/// (0, 0, 0, 0, 0.5, 1, 1, 1, 1) that interpolates section m at w = m / 4. Degree (3, 3, 3).
BSplineVolume curved_loft();

}  // namespace volspline
