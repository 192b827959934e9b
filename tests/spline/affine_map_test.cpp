#include "volspline/spline/affine_map.h"

#include <gtest/gtest.h>

#include "support/geometry_checks.h"
#include "volspline/core/error.h"

namespace volspline {
namespace {

using test_support::random_parameter;
using test_support::random_spline;

TEST(AffineMap, MapsTheSplineLikeItsControlPoints) {
  std::mt19937 rng(70);
  Eigen::MatrixXd A(3, 3);
  A << 1, 2, 0, -1, 0.5, 3, 0.2, 0, 1;
  Eigen::VectorXd b(3);
  b << 5, -1, 2;
  for (bool rational : {false, true}) {
    const auto s = random_spline<3>(rng, {2, 3, 2}, 2, 3, rational, true, 1, rational);
    const auto m = transform_affine(s, A, b);
    for (int i = 0; i < 30; ++i) {
      const auto t = random_parameter(rng, s);
      const Eigen::VectorXd expected = A * s.evaluate(t) + b;
      EXPECT_LT((m.evaluate(t) - expected).norm(), 1e-12 * (1 + expected.norm()));
    }
  }
  EXPECT_THROW(transform_affine(random_spline<2>(rng, {2, 2}, 2, 2, false), A, b), InvalidInput);
}

TEST(AffineMap, EmbedsPlanarCurvesInSpace) {
  BSplineCurve half({KnotVector::bezier(2)}, 2, {1, 0, 0, 1, -1, 0}, {1, 0, 1});
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(3, 2);
  A(0, 0) = 1;
  A(2, 1) = 1;  // the xz plane
  Eigen::VectorXd b = Eigen::Vector3d(0, 7, 0);
  const auto c = transform_affine(half, A, b);
  for (int i = 0; i <= 20; ++i) {
    const auto x = c.evaluate({i / 20.0});
    EXPECT_NEAR(x[1], 7.0, 1e-15);
    EXPECT_NEAR(std::hypot(x[0], x[2]), 1.0, 1e-15);
  }
}

template <int D>
void check_box(const TensorSpline<D>& s, std::mt19937& rng) {
  const auto [lo, hi] = bounding_box(s);
  for (int i = 0; i < 500; ++i) {
    const auto x = s.evaluate(random_parameter(rng, s));
    for (int c = 0; c < s.dimension(); ++c) {
      EXPECT_GE(x[c], lo[c] - 1e-12);
      EXPECT_LE(x[c], hi[c] + 1e-12);
    }
  }
}

TEST(BoundingBox, ContainsTheSpline) {
  std::mt19937 rng(71);
  check_box(random_spline<3>(rng, {3, 2, 2}, 3, 3, false), rng);
  check_box(random_spline<3>(rng, {2, 2, 2}, 2, 3, true, true, 1, true), rng);
  // the semicircle's middle control point is a direction: the box is still [-1,1] x [0,1]
  BSplineCurve half({KnotVector::bezier(2)}, 2, {1, 0, 0, 1, -1, 0}, {1, 0, 1});
  const auto [lo, hi] = bounding_box(half);
  EXPECT_NEAR(lo[0], -1, 1e-15);
  EXPECT_NEAR(hi[0], 1, 1e-15);
  EXPECT_NEAR(lo[1], 0, 1e-15);
  EXPECT_GE(hi[1], 1.0);
  check_box(half, rng);
  // subdivision tightens the box towards the true one, [-1, 1] x [0, 1]
  const auto [tlo, thi] = bounding_box(half, 5);
  EXPECT_NEAR(thi[1], 1.0, 2e-3);
  EXPECT_LT(thi[1], hi[1]);
}

}  // namespace
}  // namespace volspline

namespace volspline {
namespace {

TEST(BoundingBox, SubdividedBoxIsTightForUnclampedAndLongRunsOfPointsAtInfinity) {
  std::mt19937 rng(72);
  // unclamped: control points outside the domain must not widen the subdivided box
  const auto s = test_support::random_spline<2>(rng, {3, 2}, 3, 2, true, false);
  const auto [lo, hi] = bounding_box(s, 3);
  Eigen::Vector2d slo = Eigen::Vector2d::Constant(1e300), shi = -slo;
  for (int i = 0; i <= 60; ++i)
    for (int j = 0; j <= 60; ++j) {
      const auto x = s.evaluate({s.domain_min(0) + (s.domain_max(0) - s.domain_min(0)) * i / 60.0,
                                 s.domain_min(1) + (s.domain_max(1) - s.domain_min(1)) * j / 60.0});
      slo = slo.cwiseMin(x);
      shi = shi.cwiseMax(x);
    }
  const double size = (shi - slo).norm();
  for (int c = 0; c < 2; ++c) {
    EXPECT_LE(lo[c], slo[c] + 1e-12);
    EXPECT_GE(hi[c], shi[c] - 1e-12);
    EXPECT_LT(slo[c] - lo[c], 0.05 * size);
    EXPECT_LT(hi[c] - shi[c], 0.05 * size);
  }
  // degree 12 with 11 consecutive points at infinity
  std::vector<double> pts, w;
  for (int i = 0; i <= 12; ++i) {
    pts.insert(pts.end(), {std::cos(i * 0.2), std::sin(i * 0.2)});
    w.push_back(i == 0 || i == 12 ? 1.0 : 0.0);
  }
  const BSplineCurve c({KnotVector::bezier(12)}, 2, pts, w);
  const auto [clo, chi] = bounding_box(c, 2);
  const auto [elo, ehi] = bounding_box(c, 0);
  for (int i = 0; i <= 200; ++i) {
    const auto x = c.evaluate({i / 200.0});
    for (int k = 0; k < 2; ++k) {
      EXPECT_GE(x[k], clo[k] - 1e-12);
      EXPECT_LE(x[k], chi[k] + 1e-12);
      EXPECT_GE(x[k], elo[k] - 1e-12);
      EXPECT_LE(x[k], ehi[k] + 1e-12);
    }
  }
}

}  // namespace
}  // namespace volspline
