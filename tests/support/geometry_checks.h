#pragma once
// Assertions that two splines describe the same geometry.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <random>
#include <vector>

#include "support/test_splines.h"

namespace volspline::test_support {

/// `reference` and `other` agree (values and first derivatives, 1e-12 relative) at random points
/// of `other`'s domain, which must lie inside the reference's domain, and (values only: one-sided
/// derivatives may differ where the spline is only C^0) at every combination of `other`'s
/// breakpoints, domain ends included.
template <int D>
void expect_same_geometry(const TensorSpline<D>& reference, const TensorSpline<D>& other, std::mt19937& rng,
                          int samples = 60, int order = 1) {
  ASSERT_EQ(reference.dimension(), other.dimension());
  const double scale = coefficient_scale(reference);
  for (int i = 0; i < samples; ++i) {
    const auto t = random_parameter(rng, other);
    const auto a = reference.evaluate_derivatives(t, order);
    const auto b = other.evaluate_derivatives(t, order);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t j = 0; j < a.size(); ++j) {
      // first derivatives scale with the inverse span length; 1e-12 of the coefficient scale
      ASSERT_NEAR(a[j], b[j], 1e-12 * scale * (1 + std::abs(a[j]))) << "entry " << j;
    }
  }
  std::array<std::vector<double>, D> breaks;
  std::size_t combos = 1;
  for (int d = 0; d < D; ++d) {
    breaks[static_cast<std::size_t>(d)] = other.knot_vector(d).breakpoints();
    combos *= breaks[static_cast<std::size_t>(d)].size();
  }
  for (std::size_t c = 0; c < std::min<std::size_t>(combos, 2000); ++c) {
    std::array<double, D> t{};
    std::size_t rest = c;
    for (int d = 0; d < D; ++d) {
      const auto& b = breaks[static_cast<std::size_t>(d)];
      t[static_cast<std::size_t>(d)] = b[rest % b.size()];
      rest /= b.size();
    }
    const auto a = reference.evaluate(t);
    const auto b = other.evaluate(t);
    for (int j = 0; j < reference.dimension(); ++j) ASSERT_NEAR(a[j], b[j], 1e-12 * scale * (1 + std::abs(a[j]))) << "at a breakpoint";
  }
}

}  // namespace volspline::test_support
