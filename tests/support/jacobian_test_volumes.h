#pragma once
// Volumes with Jacobian determinants known in closed form, built in code for the Jacobian tests.
#include <Eigen/Dense>
#include <unsupported/Eigen/KroneckerProduct>

#include <array>
#include <cmath>
#include <functional>
#include <vector>

#include "volspline/spline/tensor_spline.h"

namespace volspline::test_support {

/// The Bézier volume of degree `degrees` on `lo`..`hi` that interpolates `f` at uniformly spaced
/// points: exact whenever f is a polynomial of at most those degrees.
inline BSplineVolume interpolating_bezier(const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& f,
                                          std::array<int, 3> degrees, Eigen::Vector3d lo, Eigen::Vector3d hi) {
  std::array<Eigen::MatrixXd, 3> collocation;
  for (int d = 0; d < 3; ++d) {
    const int n = degrees[static_cast<std::size_t>(d)];
    Eigen::MatrixXd m(n + 1, n + 1);
    for (int a = 0; a <= n; ++a) {
      const double s = static_cast<double>(a) / n;
      for (int i = 0; i <= n; ++i) {
        m(a, i) = std::tgamma(n + 1) / (std::tgamma(i + 1) * std::tgamma(n - i + 1)) * std::pow(s, i) * std::pow(1 - s, n - i);
      }
    }
    collocation[static_cast<std::size_t>(d)] = m;
  }
  // Kronecker system, first direction fastest.
  const Eigen::MatrixXd k = Eigen::kroneckerProduct(collocation[2], Eigen::kroneckerProduct(collocation[1], collocation[0])).eval();
  const int count = static_cast<int>(k.rows());
  Eigen::MatrixXd rhs(count, 3);
  int row = 0;
  for (int c = 0; c <= degrees[2]; ++c)
    for (int b = 0; b <= degrees[1]; ++b)
      for (int a = 0; a <= degrees[0]; ++a, ++row) {
        const Eigen::Vector3d s(static_cast<double>(a) / degrees[0], static_cast<double>(b) / degrees[1], static_cast<double>(c) / degrees[2]);
        rhs.row(row) = f(lo + s.cwiseProduct(hi - lo)).transpose();
      }
  const Eigen::MatrixXd points = k.fullPivLu().solve(rhs);
  std::vector<double> flat;
  for (int i = 0; i < count; ++i)
    for (int c = 0; c < 3; ++c) flat.push_back(points(i, c));
  return BSplineVolume({KnotVector::bezier(degrees[0], lo[0], hi[0]), KnotVector::bezier(degrees[1], lo[1], hi[1]),
                        KnotVector::bezier(degrees[2], lo[2], hi[2])},
                       3, flat);
}

/// The test volume x = u, y = v^3/3 - s(u, w) v, z = w with s = 0.25 + 0.2 u + 0.1 w^2 > 0
/// on [0, 1] x [-1, 1] x [0, 1]: J = v^2 - s(u, w), zero on the two sheets v = +-sqrt(s).
inline double fold_s(double u, double w) { return 0.25 + 0.2 * u + 0.1 * w * w; }
inline BSplineVolume fold_volume() {
  return interpolating_bezier(
      [](const Eigen::Vector3d& p) {
        return Eigen::Vector3d(p[0], p[1] * p[1] * p[1] / 3 - fold_s(p[0], p[2]) * p[1], p[2]);
      },
      {1, 3, 2}, Eigen::Vector3d(0, -1, 0), Eigen::Vector3d(1, 1, 1));
}

/// x = u, y = (v - c(u))^3 / 3 + e v, z = w with c(u) = 0.3 + 0.1 u, on the unit cube:
/// J = (v - c(u))^2 + e, whose minimum e is tiny against its maximum (about 0.49).
inline BSplineVolume near_singular_volume(double e) {
  return interpolating_bezier(
      [e](const Eigen::Vector3d& p) {
        const double d = p[1] - 0.3 - 0.1 * p[0];
        return Eigen::Vector3d(p[0], d * d * d / 3 + e * p[1], p[2]);
      },
      {3, 3, 1}, Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1));
}

/// J = p_u . (p_v x p_w) from the volume's own derivatives.
inline double jacobian_at(const BSplineVolume& v, const std::array<double, 3>& t) {
  const auto d = v.evaluate_derivatives(t, 1);
  const Eigen::Vector3d pu(d[3], d[4], d[5]), pv(d[6], d[7], d[8]), pw(d[9], d[10], d[11]);
  return pu.dot(pv.cross(pw));
}

}  // namespace volspline::test_support
