#include "volspline/analysis/jacobian_bezier.h"

#include <gtest/gtest.h>

#include <random>

#include "support/test_splines.h"
#include "support/jacobian_test_volumes.h"
#include "volspline/analysis/cone_bounds.h"
#include "volspline/analysis/jacobian_subdivision.h"
#include "volspline/construct/paper_examples.h"
#include "volspline/core/error.h"
#include "volspline/construct/primitives.h"
#include "volspline/spline/bezier_extraction.h"

namespace volspline {
namespace {

using test_support::jacobian_at;

// Local parameters of t in a Bézier cell.
std::array<double, 3> local(const BSplineVolume& cell, const std::array<double, 3>& t) {
  std::array<double, 3> s{};
  for (int d = 0; d < 3; ++d) s[static_cast<std::size_t>(d)] = (t[static_cast<std::size_t>(d)] - cell.domain_min(d)) / (cell.domain_max(d) - cell.domain_min(d));
  return s;
}

std::array<double, 3> random_point(std::mt19937& rng, const BSplineVolume& v) {
  std::array<double, 3> t{};
  for (int d = 0; d < 3; ++d) {
    std::uniform_real_distribution<double> x(v.domain_min(d), v.domain_max(d));
    t[static_cast<std::size_t>(d)] = x(rng);
  }
  return t;
}

TEST(JacobianBezier, PolynomialCoefficientsReproduceTheDeterminantOfTheDerivatives) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 6; ++trial) {
    const auto volume = test_support::random_spline<3>(rng, {1 + trial % 3, 2, 3 - trial % 2}, 3, 3, false);
    for (const auto& cell : bezier_pieces(volume)) {
      const auto j = jacobian_bezier_coefficients(cell, extraction_error_bound(volume));
      const auto deg = cell.degrees();
      EXPECT_EQ(j.coefficients.degrees, (std::array<int, 3>{3 * deg[0] - 1, 3 * deg[1] - 1, 3 * deg[2] - 1}));
      EXPECT_FALSE(j.homogeneous);
      for (int n = 0; n < 5; ++n) {
        const auto t = random_point(rng, cell);
        const double exact = jacobian_at(cell, t);
        EXPECT_NEAR(bernstein_evaluate(j.coefficients, local(cell, t)), exact, 1e-11 * (1 + std::abs(exact)));
      }
      EXPECT_GT(j.error_bound, 0);
      EXPECT_LT(j.error_bound, 1e-9 * (1 + bernstein_max_abs(j.coefficients)));
    }
  }
}

TEST(JacobianBezier, RationalCoefficientsAreWeightToTheFourthTimesJ) {
  std::mt19937 rng(12);
  for (const BSplineVolume& volume : {test_support::random_spline<3>(rng, {2, 2, 1}, 2, 3, true), torus(3.0, 1.0),
                                      test_support::random_spline<3>(rng, {2, 3, 2}, 2, 3, true, true, 1, true)}) {
    for (const auto& cell : bezier_pieces(volume)) {
      const auto j = jacobian_bezier_coefficients(cell, extraction_error_bound(volume));
      ASSERT_TRUE(j.homogeneous);
      const auto deg = cell.degrees();
      EXPECT_EQ(j.coefficients.degrees, (std::array<int, 3>{4 * deg[0] - 1, 4 * deg[1] - 1, 4 * deg[2] - 1}));
      for (int n = 0; n < 5; ++n) {
        const auto t = random_point(rng, cell);
        const double w = bernstein_evaluate(j.weights, local(cell, t));
        const double expected = w * w * w * w * jacobian_at(cell, t);
        EXPECT_NEAR(bernstein_evaluate(j.coefficients, local(cell, t)), expected, 1e-10 * (1 + std::abs(expected)));
      }
    }
  }
}

TEST(JacobianBezier, KnownFoldHasJacobianVSquaredMinusS) {
  const auto v = test_support::fold_volume();
  const auto j = jacobian_bezier_coefficients(v);
  for (double u : {0.0, 0.3, 1.0})
    for (double vv : {-1.0, -0.2, 0.55, 1.0})
      for (double w : {0.0, 0.7}) {
        const double expected = vv * vv - test_support::fold_s(u, w);
        EXPECT_NEAR(bernstein_evaluate(j.coefficients, local(v, {u, vv, w})), expected, 1e-13);
      }
}

TEST(JacobianBezier, RejectsWhatIsNotOneBezierCellInSpace) {
  std::mt19937 rng(13);
  EXPECT_THROW(jacobian_bezier_coefficients(test_support::random_spline<3>(rng, {2, 2, 2}, 2, 3, false)), InvalidInput);
  EXPECT_THROW(jacobian_bezier_coefficients(bezier_pieces(test_support::random_spline<3>(rng, {2, 2, 2}, 1, 2, false))[0]),
               InvalidInput);
}

// Bounds of J on random sub-boxes of random cells contain every sampled value (both methods),
// and the Bernstein bound is never wider than the cone bound there.
TEST(JacobianBounds, BothMethodsContainTheSampledRangeOnRandomCells) {
  std::mt19937 rng(14);
  std::uniform_int_distribution<int> dir(0, 2);
  std::uniform_real_distribution<double> unit(0, 1);
  int bezier_tighter = 0, cells = 0;
  for (const BSplineVolume& volume : {twisted_loft(), curved_loft(), test_support::fold_volume(),
                                      test_support::random_spline<3>(rng, {3, 2, 2}, 2, 3, false)}) {
    const JacobianSubdivision bezier(volume, JacobianBoundMethod::Bezier), cone(volume, JacobianBoundMethod::Cone);
    auto b_roots = bezier.roots();
    auto c_roots = cone.roots();
    for (std::size_t r = 0; r < b_roots.size(); ++r) {
      JacobianCell b = b_roots[r], c = c_roots[r];
      for (int depth = 0; depth < 6; ++depth) {
        const int d = dir(rng);
        auto [b0, b1] = bezier.split(b, d);
        auto [c0, c1] = cone.split(c, d);
        const bool first = unit(rng) < 0.5;
        b = first ? b0 : b1;
        c = first ? c0 : c1;
        ASSERT_EQ(b.origin, c.origin);
        const Eigen::Vector3d lo = bezier.corner_parameter(b, 0), hi = bezier.corner_parameter(b, 7);
        for (int n = 0; n < 40; ++n) {
          std::array<double, 3> t{};
          for (int e = 0; e < 3; ++e) t[static_cast<std::size_t>(e)] = lo[e] + unit(rng) * (hi[e] - lo[e]);
          const double j = jacobian_at(volume, t);
          const double slack = 1e-12 * bezier.scale();
          EXPECT_GE(j, b.lower - slack);
          EXPECT_LE(j, b.upper + slack);
          EXPECT_GE(j, c.lower - slack);
          EXPECT_LE(j, c.upper + slack);
        }
        ++cells;
        if (b.width() <= c.width()) ++bezier_tighter;
      }
    }
  }
  EXPECT_EQ(bezier_tighter, cells);
}

// The Bernstein coefficients converge to the values of J at their Greville points as O(h^2):
// halving a cell in all three directions divides the largest difference by about 4 (and with it
// the excess of the bound over the true range).
TEST(JacobianBounds, BernsteinBoundsConvergeQuadratically) {
  const auto volume = twisted_loft();
  const JacobianSubdivision sub(volume, JacobianBoundMethod::Bezier);
  JacobianCell cell = sub.roots()[0];
  std::vector<double> distance;
  for (int level = 0; level < 8; ++level) {
    const BernsteinTensor<3>& c = cell.jacobian.coefficients;
    const Eigen::Vector3d lo = sub.corner_parameter(cell, 0), hi = sub.corner_parameter(cell, 7);
    double d = 0;
    for (int k = 0; k < c.size(2); ++k)
      for (int j = 0; j < c.size(1); ++j)
        for (int i = 0; i < c.size(0); ++i) {
          const std::array<double, 3> t{lo[0] + (hi[0] - lo[0]) * i / c.degrees[0], lo[1] + (hi[1] - lo[1]) * j / c.degrees[1],
                                        lo[2] + (hi[2] - lo[2]) * k / c.degrees[2]};
          d = std::max(d, std::abs(c.at(i, j, k) - jacobian_at(volume, t)));
        }
    distance.push_back(d);
    for (int e = 0; e < 3; ++e) cell = sub.split(cell, e).first;
  }
  // The ratio tends to 4 from below as the cells shrink.
  for (std::size_t i = 1; i < distance.size(); ++i) {
    const double ratio = distance[i - 1] / distance[i];
    if (i < 4) continue;  // pre-asymptotic on the whole piece
    EXPECT_GT(ratio, i < 6 ? 3.0 : 3.6) << "level " << i;
    EXPECT_LT(ratio, 4.4) << "level " << i;
  }
}

TEST(ConeBounds, ConesOfKnownSets) {
  const Cone c = bounding_cone({{1, 0, 0}, {0, 1, 0}});
  EXPECT_NEAR(c.spread, M_PI / 4, 1e-15);
  EXPECT_NEAR(c.axis.dot(Eigen::Vector3d(1, 1, 0).normalized()), 1, 1e-15);
  EXPECT_EQ(bounding_cone({{1, 0, 0}, {0, 0, 0}}).spread, M_PI);
  EXPECT_NEAR(bounding_cone({{1, 0, 0}, {-1, 0.1, 0}}).spread, M_PI / 2 - std::atan(0.05) / 1, 1e-3);
  EXPECT_EQ(bounding_cone({{1, 0, 0}, {-1, 0.1, 0}, {0, -1, 0}}).spread, M_PI);
  // Orthonormal frames: J in [lengths] exactly at the axes.
  const auto b = cone_jacobian_bound({{2, 0, 0}}, {{0, 3, 0}}, {{0, 0, 0.5}});
  EXPECT_NEAR(b.first, 3, 1e-8);
  EXPECT_NEAR(b.second, 3, 1e-8);
}

}  // namespace
}  // namespace volspline
