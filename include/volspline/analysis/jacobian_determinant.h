#pragma once
// The Jacobian determinant of a trivariate map V at a point, J = det[V_u V_v V_w] =
// V_u · (V_v × V_w) (Joy–Duchaineau 1999 §3: J > 0 where V is a regular, orientation-preserving
// map; its zero set is the implicit part of a solid's boundary, Theorem 4.1), and its gradient
// from second partials (§6: J_u = |V_uu V_v V_w| + |V_u V_uv V_w| + |V_u V_v V_uw|, likewise for
// v and w), the one place these formulas are written. The kernels are inline: they run once per
// sample in quadrature, isosurface and export loops. Bounds of J over a cell are
// analysis/jacobian_bezier.h and analysis/cone_bounds.h.
#include <cstddef>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "volspline/spline/tensor_spline.h"

namespace volspline {

/// det[pu pv pw] = pu · (pv × pw).
inline double jacobian_determinant(const Eigen::Vector3d& pu, const Eigen::Vector3d& pv, const Eigen::Vector3d& pw) {
  return pu.dot(pv.cross(pw));
}

/// J from a flat array of partial derivatives in derivative_multi_indices order (the point
/// first, then V_u, V_v, V_w): partial alpha starts at derivatives + alpha * stride, and its first
/// three numbers are x, y, z. stride = dimension for one point of evaluate_derivatives or
/// evaluate_points (order >= 1); stride = num_points * dimension, with derivatives pointing at
/// the point's x, for one point of evaluate_grid.
inline double jacobian_determinant(const double* derivatives, std::ptrdiff_t stride = 3) {
  const auto partial = [&](std::ptrdiff_t alpha) { return Eigen::Vector3d(Eigen::Map<const Eigen::Vector3d>(derivatives + alpha * stride)); };
  return jacobian_determinant(partial(1), partial(2), partial(3));
}

/// J and its gradient (J_u, J_v, J_w) at a point.
struct JacobianWithGradient {
  double value = 0;
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero();
};

/// J and its gradient from partials up to order 2, laid out as for jacobian_determinant(const
/// double*, stride): V, V_u, V_v, V_w, V_uu, V_uv, V_uw, V_vv, V_vw, V_ww.
inline JacobianWithGradient jacobian_with_gradient(const double* derivatives, std::ptrdiff_t stride = 3) {
  const auto partial = [&](std::ptrdiff_t alpha) { return Eigen::Vector3d(Eigen::Map<const Eigen::Vector3d>(derivatives + alpha * stride)); };
  const Eigen::Vector3d pu = partial(1), pv = partial(2), pw = partial(3), puu = partial(4), puv = partial(5), puw = partial(6),
                        pvv = partial(7), pvw = partial(8), pww = partial(9);
  const auto det = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) { return jacobian_determinant(a, b, c); };
  JacobianWithGradient s;
  s.value = det(pu, pv, pw);
  s.gradient = {det(puu, pv, pw) + det(pu, puv, pw) + det(pu, pv, puw), det(puv, pv, pw) + det(pu, pvv, pw) + det(pu, pv, pvw),
                det(puw, pv, pw) + det(pu, pvw, pw) + det(pu, pv, pww)};
  return s;
}

/// J of `volume` at t. \throw InvalidInput if the volume is not in R^3 or t is outside its
/// domain.
double jacobian_determinant(const BSplineVolume& volume, const BSplineVolume::Parameter& t);

/// J and its gradient of `volume` at t. \throw InvalidInput as jacobian_determinant.
JacobianWithGradient jacobian_with_gradient(const BSplineVolume& volume, const BSplineVolume::Parameter& t);

}  // namespace volspline
