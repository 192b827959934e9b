#include "construct/piecewise_bernstein.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "support/test_splines.h"

namespace volspline {
namespace {

using namespace detail;

// Values of piece s at global parameter t.
std::vector<double> value_at(const PiecewiseBernstein& f, const std::vector<double>& breaks, double t) {
  const std::size_t s = std::min<std::size_t>(
      static_cast<std::size_t>(std::upper_bound(breaks.begin(), breaks.end(), t) - breaks.begin()) - 1, f.size() - 1);
  std::vector<double> v(static_cast<std::size_t>(f[s].components));
  bernstein_evaluate(f[s], {(t - breaks[s]) / (breaks[s + 1] - breaks[s])}, v.data());
  return v;
}

// A B-spline cut into Bézier pieces and assembled again by blossoming (de Boor-Fix) is itself:
// same knots, same coefficients.
TEST(PiecewiseBernstein, BlossomsReassembleTheBSpline) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 12; ++trial) {
    const auto curve = test_support::random_spline<1>(rng, {1 + trial % 4}, 4, 3, trial % 2 == 1);
    const KnotVector& kv = curve.knot_vector(0);
    const auto breaks = kv.breakpoints();
    std::vector<int> smoothness(breaks.size(), 0);
    for (std::size_t i = 1; i + 1 < breaks.size(); ++i) smoothness[i] = kv.degree() - kv.multiplicity(breaks[i]);
    const auto pieces = homogeneous_pieces(curve, breaks);
    ASSERT_EQ(pieces.size() + 1, breaks.size());
    const auto [knots, coefficients] = to_bspline(pieces, breaks, smoothness);
    EXPECT_EQ(knots, kv);
    const auto& h = curve.homogeneous();
    const int cs = curve.coefficient_size();
    for (int i = 0; i < kv.num_basis(); ++i)
      for (int c = 0; c < cs; ++c) EXPECT_NEAR(coefficients(i, c), h[static_cast<std::size_t>(i * cs + c)], 1e-12) << trial;
  }
}

TEST(PiecewiseBernstein, ProductElevationAndEqualityAreSpanBySpan) {
  std::mt19937 rng(6);
  // Different degrees and knots over one domain, as a sweep's path and frame curves.
  std::uniform_real_distribution<double> coordinate(-1, 1);
  auto random_points = [&](int n) {
    std::vector<double> p(static_cast<std::size_t>(n));
    for (double& x : p) x = coordinate(rng);
    return p;
  };
  const BSplineCurve a({KnotVector::uniform_clamped(2, 3)}, 1, random_points(5));
  const BSplineCurve b({KnotVector::uniform_clamped(3, 2)}, 3, random_points(15));
  std::vector<double> breaks = a.knot_vector(0).breakpoints();
  const auto more = b.knot_vector(0).breakpoints();
  breaks.insert(breaks.end(), more.begin(), more.end());
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
  const auto pa = homogeneous_pieces(a, breaks), pb = homogeneous_pieces(b, breaks);
  const auto product = multiply(pa, pb);
  std::uniform_real_distribution<double> t(breaks.front(), breaks.back());
  for (int n = 0; n < 40; ++n) {
    const double x = t(rng);
    const auto pab = value_at(product, breaks, x);
    const auto va = a.evaluate({x}), vb = b.evaluate({x});
    for (std::size_t c = 0; c < 3; ++c) EXPECT_NEAR(pab[c], va[0] * vb[c], 1e-12);
  }
  EXPECT_TRUE(same_function(pb, elevate(pb, 5)));
  auto changed = pb;
  changed.back().coefficients.front() += 1e-9;
  EXPECT_FALSE(same_function(pb, changed));
  EXPECT_TRUE(same_function(multiply(constant_one(pb.size()), pb), pb));
  EXPECT_EQ(components(pb, 1, 2).front().components, 2);
}

}  // namespace
}  // namespace volspline
