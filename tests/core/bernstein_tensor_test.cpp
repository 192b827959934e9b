#include "volspline/core/bernstein_tensor.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace volspline {
namespace {

BernsteinTensor random_tensor(std::mt19937& rng, std::array<int, 3> degrees) {
  BernsteinTensor f(degrees);
  std::uniform_real_distribution<double> c(-1, 1);
  for (double& x : f.coefficients) x = c(rng);
  return f;
}

// Direct sum of c_ijk B_i(s) B_j(t) B_k(r), an independent evaluation.
double evaluate_by_basis(const BernsteinTensor& f, const std::array<double, 3>& s) {
  auto basis = [](int n, int i, double x) { return std::tgamma(n + 1) / (std::tgamma(i + 1) * std::tgamma(n - i + 1)) * std::pow(x, i) * std::pow(1 - x, n - i); };
  double sum = 0;
  for (int k = 0; k < f.size(2); ++k)
    for (int j = 0; j < f.size(1); ++j)
      for (int i = 0; i < f.size(0); ++i)
        sum += f.at(i, j, k) * basis(f.degrees[0], i, s[0]) * basis(f.degrees[1], j, s[1]) * basis(f.degrees[2], k, s[2]);
  return sum;
}

TEST(BernsteinTensor, DeCasteljauMatchesTheBasisSum) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> t(0, 1);
  const auto f = random_tensor(rng, {3, 5, 2});
  for (int n = 0; n < 50; ++n) {
    const std::array<double, 3> s{t(rng), t(rng), t(rng)};
    EXPECT_NEAR(bernstein_evaluate(f, s), evaluate_by_basis(f, s), 1e-13);
  }
}

TEST(BernsteinTensor, SplitPiecesReproduceThePolynomial) {
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> t(0, 1);
  const auto f = random_tensor(rng, {4, 2, 3});
  for (int d = 0; d < 3; ++d) {
    const double at = 0.3;
    const auto [left, right] = bernstein_split(f, d, at);
    for (int n = 0; n < 30; ++n) {
      std::array<double, 3> s{t(rng), t(rng), t(rng)};
      const double x = s[static_cast<std::size_t>(d)];
      std::array<double, 3> global = s;
      global[static_cast<std::size_t>(d)] = at * x;
      EXPECT_NEAR(bernstein_evaluate(left, s), bernstein_evaluate(f, global), 1e-13);
      global[static_cast<std::size_t>(d)] = at + (1 - at) * x;
      EXPECT_NEAR(bernstein_evaluate(right, s), bernstein_evaluate(f, global), 1e-13);
    }
  }
}

TEST(BernsteinTensor, ProductAndElevationAreExactIdentities) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> t(0, 1);
  const auto f = random_tensor(rng, {2, 3, 1}), g = random_tensor(rng, {3, 1, 2});
  const auto h = bernstein_product(f, g);
  EXPECT_EQ(h.degrees, (std::array<int, 3>{5, 4, 3}));
  const auto e = bernstein_elevate(f, {4, 4, 4});
  for (int n = 0; n < 30; ++n) {
    const std::array<double, 3> s{t(rng), t(rng), t(rng)};
    EXPECT_NEAR(bernstein_evaluate(h, s), bernstein_evaluate(f, s) * bernstein_evaluate(g, s), 1e-13);
    EXPECT_NEAR(bernstein_evaluate(e, s), bernstein_evaluate(f, s), 1e-13);
  }
}

TEST(BernsteinTensor, DerivativeMatchesFiniteDifferences) {
  std::mt19937 rng(4);
  const auto f = random_tensor(rng, {3, 4, 2});
  const std::array<double, 3> s{0.3, 0.6, 0.45};
  const double h = 1e-6;
  for (int d = 0; d < 3; ++d) {
    auto plus = s, minus = s;
    plus[static_cast<std::size_t>(d)] += h;
    minus[static_cast<std::size_t>(d)] -= h;
    const double fd = (bernstein_evaluate(f, plus) - bernstein_evaluate(f, minus)) / (2 * h);
    EXPECT_NEAR(bernstein_evaluate(bernstein_derivative(f, d), s), fd, 1e-8);
  }
}

TEST(BernsteinTensor, CoefficientRangeContainsEverySampleAndEndsAreInterpolated) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> t(0, 1);
  const auto f = random_tensor(rng, {3, 3, 3});
  const auto [lo, hi] = bernstein_coefficient_range(f);
  for (int n = 0; n < 200; ++n) {
    const double v = bernstein_evaluate(f, {t(rng), t(rng), t(rng)});
    EXPECT_GE(v, lo);
    EXPECT_LE(v, hi);
  }
  EXPECT_DOUBLE_EQ(bernstein_evaluate(f, {1, 0, 1}), f.at(3, 0, 3));
}

}  // namespace
}  // namespace volspline
