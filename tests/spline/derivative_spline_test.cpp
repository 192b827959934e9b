#include "volspline/spline/derivative_spline.h"

#include <gtest/gtest.h>

#include "support/geometry_checks.h"
#include "volspline/core/error.h"

namespace volspline {
namespace {

using test_support::random_parameter;
using test_support::random_spline;

// The derivative spline's value equals the evaluated partial derivative, and differentiating it
// again gives the second partials: Joy-Duchaineau §3 against evaluate_derivatives.
template <int D>
void check_derivative_spline(const TensorSpline<D>& s, std::mt19937& rng) {
  const auto alphas = derivative_multi_indices<D>(2);
  const int k = s.dimension();
  for (int d = 0; d < D; ++d) {
    if (s.knot_vector(d).degree() < 2) continue;
    const auto ds = derivative_spline(s, d);
    EXPECT_EQ(ds.knot_vector(d).degree(), s.knot_vector(d).degree() - 1);
    const double scale = 1e-11 * test_support::coefficient_scale(ds);
    for (int i = 0; i < 40; ++i) {
      const auto t = random_parameter(rng, s);
      const auto exact = s.evaluate_derivatives(t, 2);
      const auto first = ds.evaluate_derivatives(t, 1);
      for (int c = 0; c < k; ++c) EXPECT_NEAR(first[static_cast<std::size_t>(c)], exact[static_cast<std::size_t>((1 + d) * k + c)], scale);
      for (int e = 0; e < D; ++e) {
        std::array<int, D> alpha{};
        alpha[static_cast<std::size_t>(d)] += 1;
        alpha[static_cast<std::size_t>(e)] += 1;
        const auto pos = std::find(alphas.begin(), alphas.end(), alpha) - alphas.begin();
        for (int c = 0; c < k; ++c)
          EXPECT_NEAR(first[static_cast<std::size_t>((1 + e) * k + c)], exact[static_cast<std::size_t>(pos * k + c)], 10 * scale);
      }
    }
  }
}

TEST(DerivativeSpline, AgreesWithEvaluatedDerivatives) {
  std::mt19937 rng(50);
  check_derivative_spline(random_spline<1>(rng, {4}, 4, 2, false, false, 3), rng);
  check_derivative_spline(random_spline<2>(rng, {3, 2}, 3, 3, false), rng);
  check_derivative_spline(random_spline<3>(rng, {3, 3, 2}, 3, 3, false, true, 3), rng);
  check_derivative_spline(random_spline<4>(rng, {2, 2, 3, 2}, 2, 1, false), rng);
}

TEST(DerivativeSpline, HandlesDiscontinuousKnots) {
  BSplineCurve c({KnotVector(2, {0, 0, 0, 0.5, 0.5, 0.5, 1, 1, 1})}, 1, {0, 1, 4, 2, 3, 7});
  const auto d = derivative_spline(c, 0);
  std::mt19937 rng(51);
  for (int i = 0; i < 50; ++i) {
    const auto t = random_parameter(rng, c);
    EXPECT_NEAR(d.evaluate(t)[0], c.evaluate_derivatives(t, 1)[1], 1e-12);
  }
}

TEST(DerivativeSpline, RejectsRationalAndLinear) {
  std::mt19937 rng(52);
  EXPECT_THROW(derivative_spline(random_spline<2>(rng, {2, 2}, 2, 3, true), 0), InvalidInput);
  EXPECT_THROW(derivative_spline(random_spline<2>(rng, {1, 2}, 2, 3, false), 0), InvalidInput);
}

}  // namespace
}  // namespace volspline
