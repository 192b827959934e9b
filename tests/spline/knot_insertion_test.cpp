#include "volspline/spline/knot_insertion.h"

#include <gtest/gtest.h>

#include "support/geometry_checks.h"
#include "volspline/core/error.h"

namespace volspline {
namespace {

using test_support::expect_same_geometry;
using test_support::random_spline;

template <int D>
void check_insertion(const TensorSpline<D>& s, std::mt19937& rng) {
  for (int d = 0; d < D; ++d) {
    const KnotVector& kv = s.knot_vector(d);
    std::uniform_real_distribution<double> u(kv.domain_min(), kv.domain_max());
    const double t = u(rng);
    const auto once = insert_knot(s, d, t);
    EXPECT_EQ(once.knot_vector(d).multiplicity(t), kv.multiplicity(t) + 1);
    EXPECT_EQ(once.num_control_points()[static_cast<std::size_t>(d)], kv.num_basis() + 1);
    expect_same_geometry(s, once, rng);
    // to full multiplicity at an existing breakpoint, and at the domain ends
    const double b = kv.breakpoints()[1];
    expect_same_geometry(s, insert_knot(s, d, b, kv.degree() + 1 - kv.multiplicity(b)), rng);
    expect_same_geometry(s, refine_knots(s, d, {u(rng), u(rng), u(rng), t}), rng);
  }
  expect_same_geometry(s, clamp(s), rng);
  auto c = clamp(s);
  for (int d = 0; d < D; ++d) {
    EXPECT_TRUE(c.knot_vector(d).is_clamped());
    EXPECT_EQ(c.domain_min(d), s.domain_min(d));
    EXPECT_EQ(c.domain_max(d), s.domain_max(d));
  }
}

TEST(KnotInsertion, LeavesGeometryUnchanged) {
  std::mt19937 rng(20);
  check_insertion(random_spline<1>(rng, {3}, 3, 2, false, false), rng);
  check_insertion(random_spline<2>(rng, {2, 3}, 3, 3, true, true, 2, true), rng);
  check_insertion(random_spline<3>(rng, {3, 2, 1}, 3, 3, false, false), rng);
  check_insertion(random_spline<3>(rng, {2, 2, 3}, 2, 3, true, false, 2, true), rng);
  check_insertion(random_spline<4>(rng, {1, 2, 2, 1}, 2, 2, true), rng);
}

TEST(KnotInsertion, RejectsExcessMultiplicityAndOutsideKnots) {
  std::mt19937 rng(21);
  const auto s = random_spline<2>(rng, {2, 2}, 2, 3, false);
  EXPECT_THROW(insert_knot(s, 0, s.domain_min(0), 1), InvalidInput);  // already p+1
  EXPECT_THROW(insert_knot(s, 0, s.domain_max(0) + 1, 1), InvalidInput);
  EXPECT_THROW(insert_knot(s, 2, 0.5, 1), InvalidInput);
}

}  // namespace
}  // namespace volspline
