#pragma once
// Assertions that two splines describe the same geometry.
#include <gtest/gtest.h>

#include <random>

#include "spline/test_splines.h"

namespace volspline::testing {

/// `reference` and `other` agree (values and first derivatives, 1e-12 relative) at random points
/// of `other`'s domain, which must lie inside the reference's domain.
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
}

}  // namespace volspline::testing
