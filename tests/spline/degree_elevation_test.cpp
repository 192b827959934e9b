#include "volspline/spline/degree_elevation.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "support/geometry_checks.h"

namespace volspline {
namespace {

using test_support::expect_same_geometry;
using test_support::random_spline;

template <int D>
void check_elevation(const TensorSpline<D>& s, std::mt19937& rng) {
  for (int d = 0; d < D; ++d) {
    for (int times : {1, 2, 3}) {
      const auto e = elevate_degree(s, d, times);
      const KnotVector& before = s.knot_vector(d);
      const KnotVector& after = e.knot_vector(d);
      EXPECT_EQ(after.degree(), before.degree() + times);
      // continuity is kept: every breakpoint's multiplicity grows by `times`
      const auto breaks = before.breakpoints();
      EXPECT_EQ(after.multiplicity(breaks.front()), after.degree() + 1);  // elevation clamps the ends
      EXPECT_EQ(after.multiplicity(breaks.back()), after.degree() + 1);
      for (double b : std::vector<double>(breaks.begin() + 1, breaks.end() - 1)) {
        const int m = std::min(before.multiplicity(b), before.degree() + 1);
        EXPECT_EQ(after.multiplicity(b), std::min(m + times, after.degree() + 1)) << "knot " << b;
      }
      expect_same_geometry(s, e, rng, 30, 2);
    }
  }
}

TEST(DegreeElevation, LeavesGeometryUnchanged) {
  std::mt19937 rng(40);
  check_elevation(random_spline<1>(rng, {1}, 4, 2, false), rng);
  check_elevation(random_spline<1>(rng, {4}, 4, 3, true, true, 4), rng);  // interior multiplicity up to p
  check_elevation(random_spline<2>(rng, {2, 3}, 3, 3, true, true, 2, true), rng);
  check_elevation(random_spline<3>(rng, {3, 2, 1}, 3, 3, false, false), rng);
  check_elevation(random_spline<4>(rng, {1, 2, 1, 2}, 2, 2, true), rng);
}

TEST(DegreeElevation, HandlesDiscontinuousKnots) {
  // an interior knot of multiplicity p+1 splits the spline into independent pieces
  BSplineCurve c({KnotVector(2, {0, 0, 0, 0.5, 0.5, 0.5, 1, 1, 1})}, 2, {0, 0, 1, 1, 2, 0, 3, 3, 4, 1, 5, 0});
  std::mt19937 rng(41);
  const auto e = elevate_degree(c, 0, 2);
  EXPECT_EQ(e.knot_vector(0).multiplicity(0.5), 5);
  expect_same_geometry(c, e, rng, 50, 2);
}

TEST(DegreeElevation, RemovesPointsAtInfinity) {
  BSplineCurve half({KnotVector::bezier(2)}, 2, {1, 0, 0, 1, -1, 0}, {1, 0, 1});
  const auto e = elevate_degree(half, 0, 1);
  for (double w : e.weights()) EXPECT_GT(w, 0.0);
  std::mt19937 rng(42);
  expect_same_geometry(half, e, rng, 50, 2);
}

}  // namespace
}  // namespace volspline
