#include "volspline/core/binomial.h"

#include <gtest/gtest.h>

#include <cmath>

namespace volspline {
namespace {

TEST(Binomial, PascalRuleSymmetryAndRowSums) {
  for (int n = 1; n <= 56; ++n) {
    double row = 0;
    for (int k = 0; k <= n; ++k) {
      // Every entry below 2^53 is exact, so the identities hold exactly.
      EXPECT_EQ(binomial_coefficient(n, k), binomial_coefficient(n - 1, k - 1) + binomial_coefficient(n - 1, k));
      EXPECT_EQ(binomial_coefficient(n, k), binomial_coefficient(n, n - k));
      row += binomial_coefficient(n, k);
    }
    EXPECT_EQ(row, std::ldexp(1.0, n));
  }
  EXPECT_EQ(binomial_coefficient(10, 3), 120.0);
  EXPECT_EQ(binomial_coefficient(56, 28), 7648690600760440.0);
  EXPECT_EQ(binomial_coefficient(5, -1), 0.0);
  EXPECT_EQ(binomial_coefficient(5, 6), 0.0);
}

TEST(Binomial, TableAndProductFormulaAgreeBeyondExactness) {
  // Past 2^53 both are rounded; they agree to a few units of roundoff per row.
  for (int n : {100, 255, 256}) {
    for (int k : {1, 7, n / 2}) {
      double b = 1.0;
      for (int i = 1; i <= k; ++i) b = b * (n - k + i) / i;
      EXPECT_NEAR(binomial_coefficient(n, k), b, 1e-13 * b) << n << " " << k;
    }
  }
  EXPECT_NEAR(binomial_coefficient(300, 2), 44850.0, 0.0);
}

}  // namespace
}  // namespace volspline
