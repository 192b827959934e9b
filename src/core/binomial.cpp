#include "volspline/core/binomial.h"

#include <cstddef>
#include <string>
#include <vector>

#include "volspline/core/error.h"

namespace volspline {

namespace {

// Row n starts at n (n + 1) / 2.
const std::vector<double>& pascal_triangle() {
  static const std::vector<double> table = [] {
    std::vector<double> t(static_cast<std::size_t>((kBinomialTableOrder + 1) * (kBinomialTableOrder + 2) / 2));
    for (int n = 0; n <= kBinomialTableOrder; ++n) {
      double* row = t.data() + static_cast<std::size_t>(n * (n + 1) / 2);
      const double* above = t.data() + static_cast<std::size_t>((n - 1) * n / 2);
      row[0] = row[n] = 1.0;
      for (int k = 1; k < n; ++k) row[k] = above[k - 1] + above[k];
    }
    return t;
  }();
  return table;
}

}  // namespace

double binomial_coefficient(int n, int k) {
  if (k < 0 || k > n) return 0.0;
  if (n <= kBinomialTableOrder) return pascal_triangle()[static_cast<std::size_t>(n * (n + 1) / 2 + k)];
  double b = 1.0;
  for (int i = 1; i <= k; ++i) b = b * (n - k + i) / i;
  return b;
}

const double* binomial_row(int n) {
  if (n < 0 || n > kBinomialTableOrder) {
    throw InvalidInput("binomial_row: row " + std::to_string(n) + " is outside the table (0.." + std::to_string(kBinomialTableOrder) + ")");
  }
  return pascal_triangle().data() + static_cast<std::size_t>(n * (n + 1) / 2);
}

}  // namespace volspline
