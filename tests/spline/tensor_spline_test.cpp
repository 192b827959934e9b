#include "volspline/spline/tensor_spline.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "support/test_splines.h"
#include "volspline/core/error.h"

namespace volspline {
namespace {

using test_support::coefficient_scale;
using test_support::random_parameter;
using test_support::random_spline;

// Derivatives of every order up to 3 against central differences of the order below, for
// polynomial and rational splines of every D.
template <int D>
void check_derivatives(const TensorSpline<D>& s, std::mt19937& rng) {
  const int order = 3;
  const auto alphas = derivative_multi_indices<D>(order);
  const int k = s.dimension();
  const double h = 1e-6;
  for (int trial = 0; trial < 10; ++trial) {
    auto t = random_parameter(rng, s);
    // stay away from knots so the finite differences see one polynomial piece
    bool near_knot = false;
    for (int d = 0; d < D; ++d)
      for (double b : s.knot_vector(d).breakpoints())
        if (std::abs(t[static_cast<std::size_t>(d)] - b) < 10 * h) near_knot = true;
    if (near_knot) continue;
    const auto exact = s.evaluate_derivatives(t, order);
    for (std::size_t a = 0; a < alphas.size(); ++a) {
      const auto& alpha = alphas[a];
      int total = 0;
      for (int x : alpha) total += x;
      if (total == 0) continue;
      // alpha = lower + e_d for the first d with alpha_d > 0
      int d = 0;
      while (alpha[static_cast<std::size_t>(d)] == 0) ++d;
      auto lower = alpha;
      lower[static_cast<std::size_t>(d)] -= 1;
      const auto pos = std::find(alphas.begin(), alphas.end(), lower) - alphas.begin();
      auto tp = t, tm = t;
      tp[static_cast<std::size_t>(d)] += h;
      tm[static_cast<std::size_t>(d)] -= h;
      const auto fp = s.evaluate_derivatives(tp, order - 1);
      const auto fm = s.evaluate_derivatives(tm, order - 1);
      for (int c = 0; c < k; ++c) {
        const double fd = (fp[static_cast<std::size_t>(pos * k + c)] - fm[static_cast<std::size_t>(pos * k + c)]) / (2 * h);
        const double ex = exact[a * static_cast<std::size_t>(k) + static_cast<std::size_t>(c)];
        EXPECT_NEAR(ex, fd, 2e-4 * (1 + std::abs(ex))) << "D=" << D << " alpha index " << a << " coordinate " << c;
      }
    }
  }
}

// The grid evaluation (the general sum-factorisation recurrence) at every point of `samples`
// against evaluate_derivatives at that point (the fixed-size kernels where the degrees have
// them), value and partials up to `order`.
template <int D>
void expect_grid_equals_single_evaluations(const TensorSpline<D>& s, const std::array<std::vector<double>, D>& samples, int order,
                                          double tolerance) {
  const auto grid = s.evaluate_grid(samples, order);
  const std::size_t n_alpha = derivative_multi_indices<D>(order).size();
  std::size_t points = 1;
  for (const auto& v : samples) points *= v.size();
  const int k = s.dimension();
  for (std::size_t pt = 0; pt < points; ++pt) {
    std::array<double, D> t{};
    std::size_t rest = pt;
    for (std::size_t d = 0; d < static_cast<std::size_t>(D); ++d) {
      t[d] = samples[d][rest % samples[d].size()];
      rest /= samples[d].size();
    }
    const auto single = s.evaluate_derivatives(t, order);
    for (std::size_t a = 0; a < n_alpha; ++a)
      for (int c = 0; c < k; ++c) {
        const double g = grid[(a * points + pt) * static_cast<std::size_t>(k) + static_cast<std::size_t>(c)];
        const double x = single[a * static_cast<std::size_t>(k) + static_cast<std::size_t>(c)];
        ASSERT_NEAR(g, x, tolerance * (1 + std::abs(x))) << "D=" << D << " order " << order << " point " << pt << " alpha " << a;
      }
  }
}

// Three random parameters per direction and the first interior breakpoint (a knot).
template <int D>
std::array<std::vector<double>, D> random_samples_and_a_knot(const TensorSpline<D>& s, std::mt19937& rng) {
  std::array<std::vector<double>, D> samples;
  for (int d = 0; d < D; ++d) {
    std::uniform_real_distribution<double> at(s.domain_min(d), s.domain_max(d));
    for (int i = 0; i < 3; ++i) samples[static_cast<std::size_t>(d)].push_back(at(rng));
    samples[static_cast<std::size_t>(d)].push_back(s.knot_vector(d).breakpoints()[1]);
  }
  return samples;
}

TEST(TensorSpline, DerivativeMultiIndexOrder) {
  const auto a = derivative_multi_indices<3>(2);
  const std::vector<std::array<int, 3>> expected{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {2, 0, 0},
                                                  {1, 1, 0}, {1, 0, 1}, {0, 2, 0}, {0, 1, 1}, {0, 0, 2}};
  EXPECT_EQ(a, expected);
  EXPECT_EQ(derivative_multi_indices<4>(3).size(), 35u);  // C(3+4, 4)
  EXPECT_EQ(derivative_multi_indices<1>(5).size(), 6u);
}

TEST(TensorSpline, DerivativesMatchFiniteDifferences) {
  std::mt19937 rng(10);
  check_derivatives(random_spline<1>(rng, {4}, 3, 2, false), rng);
  check_derivatives(random_spline<1>(rng, {3}, 3, 3, true, true, 2, true), rng);
  check_derivatives(random_spline<2>(rng, {3, 2}, 3, 3, false, false), rng);
  check_derivatives(random_spline<2>(rng, {2, 3}, 2, 3, true), rng);
  check_derivatives(random_spline<3>(rng, {3, 3, 3}, 3, 3, false), rng);
  check_derivatives(random_spline<3>(rng, {2, 3, 1}, 2, 3, true, false, 2, true), rng);
  check_derivatives(random_spline<4>(rng, {2, 1, 2, 3}, 2, 3, false), rng);
  check_derivatives(random_spline<4>(rng, {1, 2, 2, 2}, 2, 4, true), rng);
}

TEST(TensorSpline, PolynomialsAreReproducedExactly) {
  // Control points at the Greville abscissae of a linear function reproduce it exactly, and a
  // tricubic volume with control points on the Greville grid is the identity map.
  std::mt19937 rng(11);
  std::array<KnotVector, 3> knots{test_support::random_knots(rng, 3, 3, true, 2), test_support::random_knots(rng, 2, 4, false, 1),
                                  test_support::random_knots(rng, 1, 2, true, 1)};
  std::vector<double> pts;
  auto greville = [&](int d, int i) {
    const auto& K = knots[static_cast<std::size_t>(d)];
    double g = 0;
    for (int j = 1; j <= K.degree(); ++j) g += K.knots()[static_cast<std::size_t>(i + j)];
    return g / K.degree();
  };
  for (int k = 0; k < knots[2].num_basis(); ++k)
    for (int j = 0; j < knots[1].num_basis(); ++j)
      for (int i = 0; i < knots[0].num_basis(); ++i) {
        pts.push_back(greville(0, i));
        pts.push_back(greville(1, j));
        pts.push_back(greville(2, k));
      }
  BSplineVolume identity(knots, 3, pts);
  for (int trial = 0; trial < 100; ++trial) {
    const auto t = random_parameter(rng, identity);
    const auto d = identity.evaluate_derivatives(t, 1);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(d[static_cast<std::size_t>(c)], t[static_cast<std::size_t>(c)], 1e-14);
      for (int e = 0; e < 3; ++e) EXPECT_NEAR(d[static_cast<std::size_t>(3 + 3 * e + c)], e == c ? 1.0 : 0.0, 1e-13);
    }
  }
}

TEST(TensorSpline, GridEvaluationEqualsScatteredEvaluation) {
  std::mt19937 rng(12);
  auto check = [&](const auto& s) {
    constexpr int D = std::decay_t<decltype(s)>::num_parameters;
    std::array<std::vector<double>, D> samples;
    for (int d = 0; d < D; ++d) {
      const int n = 3 + d;
      for (int i = 0; i < n; ++i)
        samples[static_cast<std::size_t>(d)].push_back(s.domain_min(d) + (s.domain_max(d) - s.domain_min(d)) * i / (n - 1));
      samples[static_cast<std::size_t>(d)].push_back(s.knot_vector(d).breakpoints()[1]);  // a knot
    }
    expect_grid_equals_single_evaluations<D>(s, samples, 2, 1e-11);
  };
  check(random_spline<1>(rng, {3}, 4, 2, false));
  check(random_spline<2>(rng, {3, 2}, 3, 3, true, false));
  check(random_spline<3>(rng, {3, 3, 3}, 3, 3, false));
  check(random_spline<3>(rng, {2, 1, 3}, 2, 3, true, true, 2, true));
  check(random_spline<4>(rng, {1, 2, 1, 2}, 2, 2, false));
}

// Value, first and second partials of 4-variate splines of degrees 1 to 3 in u, v, w (the
// fixed-size paths that swept solids take; second order for the trimming's Newton on folds)
// against the grid evaluation's general recurrence at the same points, and against finite
// differences: polynomial and rational, three and four numbers per control point, every degree
// the fixed paths cover and some they do not.
TEST(TensorSpline, FourVariateValueAndPartialsToOrderTwoEqualTheGeneralRecurrence) {
  std::mt19937 rng(15);
  auto check = [&](const TensorSpline<4>& s) {
    check_derivatives(s, rng);
    const auto samples = random_samples_and_a_knot(s, rng);
    for (int order = 0; order <= 2; ++order) expect_grid_equals_single_evaluations<4>(s, samples, order, 1e-12);
  };
  for (int p = 1; p <= 3; ++p) {
    check(random_spline<4>(rng, {p, p, p, 1}, 2, 3, false));
    check(random_spline<4>(rng, {p, p, p, 2}, 2, 3, true));
    check(random_spline<4>(rng, {p, p, p, 3}, 3, 3, true, false));
  }
  check(random_spline<4>(rng, {1, 2, 2, 1}, 2, 4, true));  // the ball and torus sweeps' degrees
  // Rational with three coordinates (four numbers per coefficient: the fixed kernels' case) as the
  // swept solids are, and with four (the general recurrence).
  check(random_spline<4>(rng, {1, 2, 2, 1}, 2, 3, true));
  check(random_spline<4>(rng, {1, 1, 2, 2}, 2, 3, true));  // a cylinder tumbled (Conkey–Joy Fig. 5)
  check(random_spline<4>(rng, {1, 1, 2, 2}, 2, 4, true));
  check(random_spline<4>(rng, {2, 2, 1, 1}, 2, 3, false));
  check(random_spline<4>(rng, {3, 1, 2, 2}, 2, 3, false));
  check(random_spline<4>(rng, {2, 2, 2, 7}, 1, 3, false));
  check(random_spline<4>(rng, {4, 4, 4, 2}, 1, 3, true));
}

// The 3-variate fixed kernels (value and first partials) against the grid evaluation's general
// recurrence, for the mixed orders (p_v != p_w) they cover and one they do not.
TEST(TensorSpline, ThreeVariateValueAndFirstPartialsEqualTheGeneralRecurrence) {
  std::mt19937 rng(16);
  auto check = [&](const TensorSpline<3>& s) {
    const auto samples = random_samples_and_a_knot(s, rng);
    for (int order = 0; order <= 1; ++order) expect_grid_equals_single_evaluations<3>(s, samples, order, 1e-12);
  };
  check(random_spline<3>(rng, {1, 1, 2}, 2, 3, true));
  check(random_spline<3>(rng, {3, 2, 1}, 2, 3, false));
  check(random_spline<3>(rng, {1, 1, 3}, 2, 3, true));
}

TEST(TensorSpline, ParallelBatchEqualsSingleEvaluation) {
  std::mt19937 rng(14);
  const auto s = random_spline<3>(rng, {3, 2, 3}, 3, 3, true, false, 2, true);
  std::vector<std::array<double, 3>> t(5000);
  for (auto& x : t) x = random_parameter(rng, s);
  const auto batch = s.evaluate_points(t, 1);
  for (std::size_t i = 0; i < t.size(); i += 97) {
    const auto single = s.evaluate_derivatives(t[i], 1);
    for (std::size_t j = 0; j < single.size(); ++j) EXPECT_EQ(batch[i * single.size() + j], single[j]);
  }
  t[4321][1] = 1e9;
  try {
    s.evaluate_points(t);
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.where(), "points[4321]");
  }
}

TEST(TensorSpline, RationalQuarterCircleIsExact) {
  const double r = std::sqrt(0.5);
  BSplineCurve arc({KnotVector::bezier(2)}, 2, {1, 0, 1, 1, 0, 1}, {1, r, 1});
  for (int i = 0; i <= 100; ++i) {
    const auto x = arc.evaluate({i / 100.0});
    EXPECT_NEAR(std::hypot(x[0], x[1]), 1.0, 1e-15);
  }
}

TEST(TensorSpline, WeightZeroControlPointIsAPointAtInfinity) {
  // (1,0), direction (0,1) with weight 0, (-1,0): the upper unit semicircle (Lasser, after eq. 5):
  // x(t) = ((1-t)^2 - t^2, 2t(1-t)) / ((1-t)^2 + t^2).
  BSplineCurve half({KnotVector::bezier(2)}, 2, {1, 0, 0, 1, -1, 0}, {1, 0, 1});
  for (int i = 0; i <= 50; ++i) {
    const double t = i / 50.0;
    const auto d = half.evaluate_derivatives({t}, 2);
    const double den = (1 - t) * (1 - t) + t * t;
    EXPECT_NEAR(d[0], ((1 - t) * (1 - t) - t * t) / den, 1e-15);
    EXPECT_NEAR(d[1], 2 * t * (1 - t) / den, 1e-15);
    EXPECT_NEAR(std::hypot(d[0], d[1]), 1.0, 1e-15);
    // velocity is tangent (orthogonal to the radius) and acceleration satisfies x.x'' = -|x'|^2
    EXPECT_NEAR(d[0] * d[2] + d[1] * d[3], 0.0, 1e-13);
    EXPECT_NEAR(d[0] * d[4] + d[1] * d[5], -(d[2] * d[2] + d[3] * d[3]), 1e-12);
  }
  EXPECT_NEAR(half.evaluate({0.5})[1], 1.0, 1e-15);
}

TEST(TensorSpline, FullCircleFromFourArcsIsExact) {
  const double r = std::sqrt(0.5);
  KnotVector kv(2, {0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1});
  BSplineCurve circle({kv}, 2, {1, 0, 1, 1, 0, 1, -1, 1, -1, 0, -1, -1, 0, -1, 1, -1, 1, 0}, {1, r, 1, r, 1, r, 1, r, 1});
  for (int i = 0; i <= 400; ++i) {
    const auto x = circle.evaluate({i / 400.0});
    EXPECT_NEAR(std::hypot(x[0], x[1]), 1.0, 1e-15);
  }
}

TEST(TensorSpline, RejectsVanishingDenominatorAndBadWeights) {
  // every control point influencing t = 0 has weight 0
  EXPECT_THROW(BSplineCurve({KnotVector::bezier(2)}, 2, {1, 0, 0, 1, -1, 0}, {0, 1, 1}), InvalidInput);
  try {
    BSplineCurve({KnotVector::bezier(2)}, 2, {1, 0, 0, 1, -1, 0}, {1, -1, 1});
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.where(), "weights[1]");
  }
  try {
    BSplineCurve({KnotVector::bezier(2)}, 2, {1, 0, 0, NAN, -1, 0});
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.where(), "control_points[1][1]");
  }
  EXPECT_THROW(BSplineCurve({KnotVector::bezier(2)}, 2, {1, 0, 0, 1}), InvalidInput);
}

TEST(TensorSpline, ParameterOutsideDomainIsAnError) {
  std::mt19937 rng(13);
  const auto s = random_spline<3>(rng, {2, 2, 2}, 2, 3, false);
  double out[3];
  EXPECT_THROW(s.evaluate({s.domain_max(0) + 1e-9, s.domain_min(1), s.domain_min(2)}, out), InvalidInput);
  EXPECT_THROW(s.evaluate({NAN, s.domain_min(1), s.domain_min(2)}, out), InvalidInput);
  EXPECT_NO_THROW(s.evaluate({s.domain_max(0), s.domain_max(1), s.domain_max(2)}, out));
}

}  // namespace
}  // namespace volspline

namespace volspline {
namespace {

TEST(TensorSpline, WeightsAreCheckedFromBothSidesOfADiscontinuity) {
  // Knot 1 has multiplicity p + 1: the left piece ends at control point 2, whose weight 0 would
  // send the curve to infinity as t -> 1 from the left (a right-limit check alone misses it).
  const KnotVector kv(2, {0, 0, 0, 1, 1, 1, 2, 2, 2});
  EXPECT_THROW(BSplineCurve({kv}, 2, {0, 0, 1, 1, 2, 0, 3, 3, 4, 1, 5, 0}, {1, 1, 0, 1, 1, 1}), InvalidInput);
  EXPECT_THROW(BSplineCurve({kv}, 2, {0, 0, 1, 1, 2, 0, 3, 3, 4, 1, 5, 0}, {1, 1, 1, 0, 1, 1}), InvalidInput);
  EXPECT_NO_THROW(BSplineCurve({kv}, 2, {0, 0, 1, 1, 2, 0, 3, 3, 4, 1, 5, 0}, {1, 0, 1, 1, 0, 1}));
}

TEST(TensorSpline, RoundOffNegativeHomogeneousWeightsAreZero) {
  const auto c = BSplineCurve::from_homogeneous({KnotVector::bezier(2)}, 1, true, {1, 1, 1, -1e-17, 1, 1});
  EXPECT_EQ(c.weights()[1], 0.0);
  EXPECT_THROW(BSplineCurve::from_homogeneous({KnotVector::bezier(2)}, 1, true, {1, 1, 1, -0.1, 1, 1}), InvalidInput);
}

}  // namespace
}  // namespace volspline
