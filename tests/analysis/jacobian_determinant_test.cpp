// The Jacobian determinant at a point against independent computations: a map whose J is known in
// closed form, an affine map (J = det A), and central differences of the volume itself.
#include "volspline/analysis/jacobian_determinant.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "support/jacobian_test_volumes.h"
#include "support/test_splines.h"
#include "volspline/core/error.h"

namespace volspline {
namespace {

using test_support::fold_s;
using test_support::fold_volume;

TEST(JacobianDeterminant, MatchesTheClosedFormOfTheFoldVolume) {
  // x = u, y = v^3/3 - s(u, w) v, z = w with s = 0.25 + 0.2 u + 0.1 w^2: J = v^2 - s(u, w),
  // J_u = -0.2, J_v = 2 v, J_w = -0.2 w.
  const BSplineVolume volume = fold_volume();
  std::mt19937 rng(11);
  for (int i = 0; i < 200; ++i) {
    const auto t = test_support::random_parameter(rng, volume);
    const double u = t[0], v = t[1], w = t[2];
    EXPECT_NEAR(jacobian_determinant(volume, t), v * v - fold_s(u, w), 1e-12);
    const JacobianWithGradient g = jacobian_with_gradient(volume, t);
    EXPECT_NEAR(g.value, v * v - fold_s(u, w), 1e-12);
    EXPECT_NEAR(g.gradient[0], -0.2, 1e-12);
    EXPECT_NEAR(g.gradient[1], 2 * v, 1e-12);
    EXPECT_NEAR(g.gradient[2], -0.2 * w, 1e-12);
  }
}

TEST(JacobianDeterminant, OfAnAffineMapIsTheDeterminantOfItsMatrix) {
  Eigen::Matrix3d a;
  a << 1.5, -0.3, 0.2, 0.4, 0.9, -0.7, -0.1, 0.6, 2.1;
  const Eigen::Vector3d b(0.3, -1.2, 4.0);
  const BSplineVolume volume = test_support::interpolating_bezier([&](const Eigen::Vector3d& p) { return Eigen::Vector3d(a * p + b); },
                                                                  {1, 1, 1}, Eigen::Vector3d(-1, 0, 2), Eigen::Vector3d(1, 3, 2.5));
  std::mt19937 rng(5);
  for (int i = 0; i < 50; ++i) {
    const auto t = test_support::random_parameter(rng, volume);
    EXPECT_NEAR(jacobian_determinant(volume, t), a.determinant(), 1e-12 * std::abs(a.determinant()));
    const JacobianWithGradient g = jacobian_with_gradient(volume, t);
    EXPECT_NEAR(g.gradient.norm(), 0.0, 1e-12);
  }
  // Exchanging two columns (the roles of u and v) changes the orientation: J changes sign.
  const Eigen::Vector3d pu = a.col(0), pv = a.col(1), pw = a.col(2);
  EXPECT_NEAR(jacobian_determinant(pv, pu, pw), -a.determinant(), 1e-14);
}

// V_u, V_v, V_w by central differences of V, and J as the determinant of that matrix (Eigen's LU,
// not the triple product); grad J by central differences of J.
TEST(JacobianDeterminant, AgreesWithCentralDifferencesOfARationalVolume) {
  std::mt19937 rng(23);
  for (int trial = 0; trial < 8; ++trial) {
    const BSplineVolume volume = test_support::random_spline<3>(rng, {3, 2, 3}, 1, 3, /*rational=*/true);
    for (int i = 0; i < 20; ++i) {
      auto t = test_support::random_parameter(rng, volume);
      const double h = 1e-5;
      for (int d = 0; d < 3; ++d) {
        t[static_cast<std::size_t>(d)] = std::clamp(t[static_cast<std::size_t>(d)], volume.domain_min(d) + 2 * h, volume.domain_max(d) - 2 * h);
      }
      Eigen::Matrix3d m;
      Eigen::Vector3d gradient;
      for (int d = 0; d < 3; ++d) {
        auto plus = t, minus = t;
        plus[static_cast<std::size_t>(d)] += h;
        minus[static_cast<std::size_t>(d)] -= h;
        m.col(d) = (volume.evaluate(plus) - volume.evaluate(minus)) / (2 * h);
        gradient[d] = (jacobian_determinant(volume, plus) - jacobian_determinant(volume, minus)) / (2 * h);
      }
      const double scale = m.col(0).norm() * m.col(1).norm() * m.col(2).norm();
      EXPECT_NEAR(jacobian_determinant(volume, t), m.determinant(), 1e-6 * scale);
      const JacobianWithGradient g = jacobian_with_gradient(volume, t);
      // Order 2 is evaluated by another kernel than order 1: equal up to rounding.
      EXPECT_NEAR(g.value, jacobian_determinant(volume, t), 1e-12 * scale);
      EXPECT_LT((g.gradient - gradient).norm(), 1e-5 * std::max(1.0, gradient.norm()));
    }
  }
}

// The flat-array form reads every layout the evaluators write: evaluate_derivatives (stride =
// dimension, also with attributes after x, y, z), evaluate_points and evaluate_grid.
TEST(JacobianDeterminant, ReadsEveryDerivativeLayout) {
  std::mt19937 rng(3);
  const BSplineVolume volume = test_support::random_spline<3>(rng, {2, 3, 2}, 2, 3, false);
  const BSplineVolume with_attributes = test_support::random_spline<3>(rng, {2, 2, 2}, 2, 5, false);
  std::array<std::vector<double>, 3> samples;
  for (int d = 0; d < 3; ++d) {
    for (int i = 0; i <= 4; ++i) samples[static_cast<std::size_t>(d)].push_back(volume.domain_min(d) + (volume.domain_max(d) - volume.domain_min(d)) * i / 4);
  }
  const std::vector<double> grid = volume.evaluate_grid(samples, 1);
  const std::size_t n = 125;
  std::vector<BSplineVolume::Parameter> points;
  for (std::size_t k = 0; k < 5; ++k)
    for (std::size_t j = 0; j < 5; ++j)
      for (std::size_t i = 0; i < 5; ++i) points.push_back({samples[0][i], samples[1][j], samples[2][k]});
  const std::vector<double> scattered = volume.evaluate_points(points, 1);
  for (std::size_t p = 0; p < n; ++p) {
    const auto d = volume.evaluate_derivatives(points[p], 1);
    const Eigen::Vector3d pu(d[3], d[4], d[5]), pv(d[6], d[7], d[8]), pw(d[9], d[10], d[11]);
    const double expected = Eigen::Matrix3d((Eigen::Matrix3d() << pu, pv, pw).finished()).determinant();
    const double scale = pu.norm() * pv.norm() * pw.norm();
    EXPECT_NEAR(jacobian_determinant(d.data()), expected, 1e-13 * scale);
    EXPECT_EQ(jacobian_determinant(scattered.data() + 12 * p), jacobian_determinant(d.data()));
    EXPECT_NEAR(jacobian_determinant(grid.data() + 3 * p, static_cast<std::ptrdiff_t>(3 * n)), jacobian_determinant(d.data()), 1e-12 * scale);
  }
  const auto t = test_support::random_parameter(rng, with_attributes);
  const auto d5 = with_attributes.evaluate_derivatives(t, 1);
  const Eigen::Vector3d pu(d5[5], d5[6], d5[7]), pv(d5[10], d5[11], d5[12]), pw(d5[15], d5[16], d5[17]);
  EXPECT_EQ(jacobian_determinant(d5.data(), 5), jacobian_determinant(pu, pv, pw));
}

TEST(JacobianDeterminant, RejectsVolumesOutsideR3AndPointsOutsideTheDomain) {
  std::mt19937 rng(1);
  const BSplineVolume planar = test_support::random_spline<3>(rng, {1, 1, 1}, 1, 2, false);
  EXPECT_THROW(jacobian_determinant(planar, {planar.domain_min(0), planar.domain_min(1), planar.domain_min(2)}), InvalidInput);
  EXPECT_THROW(jacobian_with_gradient(planar, {planar.domain_min(0), planar.domain_min(1), planar.domain_min(2)}), InvalidInput);
  const BSplineVolume volume = fold_volume();
  EXPECT_THROW(jacobian_determinant(volume, {2.0, 0.0, 0.5}), InvalidInput);
}

}  // namespace
}  // namespace volspline
