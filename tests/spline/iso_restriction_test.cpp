#include "volspline/spline/iso_restriction.h"

#include <gtest/gtest.h>

#include "support/geometry_checks.h"

namespace volspline {
namespace {

using test_support::random_parameter;
using test_support::random_spline;

template <int D>
void check_restriction(const TensorSpline<D>& s, std::mt19937& rng) {
  for (int d = 0; d < D; ++d) {
    std::uniform_real_distribution<double> u(s.domain_min(d), s.domain_max(d));
    for (double value : {s.domain_min(d), s.domain_max(d), u(rng), s.knot_vector(d).breakpoints()[1]}) {
      const auto r = restrict_to_iso(s, d, value);
      for (int i = 0; i < 20; ++i) {
        const auto tr = random_parameter(rng, r);
        std::array<double, D> t{};
        for (int e = 0, j = 0; e < D; ++e)
          t[static_cast<std::size_t>(e)] = e == d ? value : tr[static_cast<std::size_t>(j++)];
        const auto a = s.evaluate(t);
        const auto b = r.evaluate(tr);
        for (int c = 0; c < s.dimension(); ++c) EXPECT_NEAR(a[c], b[c], 1e-13 * test_support::coefficient_scale(s));
      }
    }
  }
}

TEST(IsoRestriction, FacesAndEdgesAreExact) {
  std::mt19937 rng(60);
  check_restriction(random_spline<2>(rng, {3, 2}, 3, 3, true, false, 2, true), rng);
  check_restriction(random_spline<3>(rng, {3, 3, 3}, 3, 3, false), rng);
  check_restriction(random_spline<3>(rng, {2, 2, 2}, 2, 3, true, true, 1, true), rng);
  check_restriction(random_spline<4>(rng, {1, 2, 2, 1}, 2, 3, false, false), rng);
}

}  // namespace
}  // namespace volspline
