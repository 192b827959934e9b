// Grid rows by sum factorisation agree with the rows evaluated point by point at the same
// parameters (two independent code paths), and the grid ends exactly at the domain's ends.
#include <gtest/gtest.h>

#include <random>

#include "support/test_splines.h"
#include "volspline/core/error.h"
#include "volspline/pipeline/object_evaluation.h"

namespace volspline {
namespace {

template <int D>
void expect_grid_matches_points(const TensorSpline<D>& spline, const std::vector<int>& counts) {
  const ModelObject object{"", false, spline, nullptr};
  for (const bool derivatives : {false, true}) {
    const auto rows = evaluate_object_on_grid(object, counts, derivatives);
    std::size_t total = 1;
    for (const int n : counts) total *= static_cast<std::size_t>(n);
    ASSERT_EQ(rows.size(), total);
    const double scale = test_support::coefficient_scale(spline);
    for (std::size_t p = 0; p < total; ++p) {
      std::vector<double> t(D);
      std::size_t rest = p;
      for (int d = 0; d < D; ++d) {
        const auto n = static_cast<std::size_t>(counts[static_cast<std::size_t>(d)]);
        const std::size_t i = rest % n;
        rest /= n;
        const double a = spline.domain_min(d), b = spline.domain_max(d);
        t[static_cast<std::size_t>(d)] = i == n - 1 ? b : a + (b - a) * static_cast<double>(i) / static_cast<double>(n - 1);
      }
      const auto expected = evaluate_object_at(object, t, derivatives);
      ASSERT_EQ(rows[p].size(), expected.size());
      for (std::size_t c = 0; c < expected.size(); ++c) EXPECT_NEAR(rows[p][c], expected[c], 1e-11 * scale) << p << ", " << c;
    }
    // The last grid point is the corner of the domain exactly, the image of its upper ends.
    std::vector<double> top(D);
    for (int d = 0; d < D; ++d) top[static_cast<std::size_t>(d)] = spline.domain_max(d);
    const Eigen::VectorXd corner = spline.evaluate([&] {
      std::array<double, D> t{};
      std::copy(top.begin(), top.end(), t.begin());
      return t;
    }());
    for (int c = 0; c < spline.dimension(); ++c) EXPECT_NEAR(rows.back()[static_cast<std::size_t>(c)], corner[c], 1e-12 * scale);
  }
}

TEST(ObjectEvaluation, GridRowsAreThePointRowsAtTheGridParameters) {
  std::mt19937 rng(31);
  expect_grid_matches_points(test_support::random_spline<1>(rng, {3}, 3, 2, true), {7});
  expect_grid_matches_points(test_support::random_spline<2>(rng, {2, 3}, 2, 3, false), {4, 5});
  expect_grid_matches_points(test_support::random_spline<3>(rng, {2, 1, 3}, 2, 3, true), {3, 4, 2});
}

TEST(ObjectEvaluation, RowsHoldThePointThenTheFirstPartials) {
  std::mt19937 rng(4);
  const auto volume = test_support::random_spline<3>(rng, {2, 2, 2}, 2, 3, false);
  const ModelObject object{"", false, volume, nullptr};
  const auto t = test_support::random_parameter(rng, volume);
  const auto row = evaluate_object_at(object, {t[0], t[1], t[2]}, true);
  ASSERT_EQ(row.size(), 12u);
  const Eigen::VectorXd x = volume.evaluate(t);
  for (int c = 0; c < 3; ++c) EXPECT_EQ(row[static_cast<std::size_t>(c)], x[c]);
  // Central differences of the point against the partials, direction by direction.
  const double h = 1e-6;
  for (int d = 0; d < 3; ++d) {
    auto plus = t, minus = t;
    plus[static_cast<std::size_t>(d)] += h;
    minus[static_cast<std::size_t>(d)] -= h;
    const Eigen::VectorXd difference = (volume.evaluate(plus) - volume.evaluate(minus)) / (2 * h);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(row[static_cast<std::size_t>(3 + 3 * d + c)], difference[c], 1e-5) << d << ", " << c;
  }
}

TEST(ObjectEvaluation, RejectsWrongCountsAndPointsOutsideTheDomain) {
  std::mt19937 rng(8);
  const ModelObject object{"", false, test_support::random_spline<2>(rng, {2, 2}, 1, 3, false), nullptr};
  EXPECT_THROW(evaluate_object_on_grid(object, {3}), InvalidInput);
  EXPECT_THROW(evaluate_object_on_grid(object, {3, 1}), InvalidInput);
  EXPECT_THROW(evaluate_object_at(object, {0.5}), InvalidInput);
  EXPECT_THROW(evaluate_object_at(object, {0.5, 1e9}), InvalidInput);
}

}  // namespace
}  // namespace volspline
