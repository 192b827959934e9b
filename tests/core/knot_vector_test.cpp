#include "volspline/core/knot_vector.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "support/test_splines.h"
#include "volspline/core/error.h"

namespace volspline {
namespace {

TEST(KnotVector, PartitionOfUnityEverywhere) {
  std::mt19937 rng(1);
  for (int trial = 0; trial < 40; ++trial) {
    const int p = 1 + trial % 5;
    const KnotVector kv = test_support::random_knots(rng, p, 4, trial % 2 == 0, p + 1);
    std::uniform_real_distribution<double> u(kv.domain_min(), kv.domain_max());
    std::vector<double> N(static_cast<std::size_t>(p + 1));
    std::vector<double> samples{kv.domain_min(), kv.domain_max()};
    for (double b : kv.breakpoints()) samples.push_back(b);
    for (int i = 0; i < 50; ++i) samples.push_back(u(rng));
    for (double t : samples) {
      const int s = kv.find_span(t);
      ASSERT_LE(kv.knots()[static_cast<std::size_t>(s)], t);
      ASSERT_LT(kv.knots()[static_cast<std::size_t>(s)], kv.knots()[static_cast<std::size_t>(s) + 1]);
      kv.basis(s, t, N.data());
      double sum = 0.0;
      for (double x : N) {
        EXPECT_GE(x, -1e-15);
        sum += x;
      }
      EXPECT_NEAR(sum, 1.0, 1e-14) << "t = " << t;
    }
  }
}

TEST(KnotVector, BasisDerivativesMatchFiniteDifferences) {
  std::mt19937 rng(2);
  for (int p = 1; p <= 5; ++p) {
    const KnotVector kv = test_support::random_knots(rng, p, 3, true, 1);
    std::uniform_real_distribution<double> u(kv.domain_min() + 0.01, kv.domain_max() - 0.01);
    const int order = p + 1;  // includes one order above the degree, which must be zero
    std::vector<double> D0((order + 1) * (p + 1)), Dp(D0.size()), Dm(D0.size());
    for (int trial = 0; trial < 20; ++trial) {
      const double t = u(rng);
      const double h = 1e-6;
      const int s = kv.find_span(t);
      if (kv.find_span(t + h) != s || kv.find_span(t - h) != s) continue;
      kv.basis_derivatives(s, t, order, D0.data());
      kv.basis_derivatives(s, t + h, order, Dp.data());
      kv.basis_derivatives(s, t - h, order, Dm.data());
      std::vector<double> N(static_cast<std::size_t>(p + 1));
      kv.basis(s, t, N.data());
      for (int j = 0; j <= p; ++j) EXPECT_NEAR(D0[static_cast<std::size_t>(j)], N[static_cast<std::size_t>(j)], 1e-15);
      for (int k = 1; k <= order; ++k)
        for (int j = 0; j <= p; ++j) {
          const std::size_t lo = static_cast<std::size_t>((k - 1) * (p + 1) + j);
          const double fd = (Dp[lo] - Dm[lo]) / (2 * h);
          const double exact = D0[static_cast<std::size_t>(k * (p + 1) + j)];
          EXPECT_NEAR(exact, fd, 1e-5 * (1 + std::abs(exact))) << "p=" << p << " k=" << k << " j=" << j;
        }
      for (int j = 0; j <= p; ++j) EXPECT_EQ(D0[static_cast<std::size_t>(order * (p + 1) + j)], 0.0);
    }
  }
}

TEST(KnotVector, UnclampedDomainIsInnerKnots) {
  const KnotVector kv(2, {0, 1, 2, 3, 4, 5});
  EXPECT_EQ(kv.domain_min(), 2.0);
  EXPECT_EQ(kv.domain_max(), 3.0);
  EXPECT_FALSE(kv.is_clamped());
  EXPECT_EQ(kv.num_basis(), 3);
  EXPECT_EQ(kv.find_span(3.0), 2);
}

TEST(KnotVector, RejectsBadKnotsWithTheirIndex) {
  auto where = [](int p, std::vector<double> k) {
    try {
      KnotVector kv(p, std::move(k));
    } catch (const InvalidInput& e) {
      return e.where();
    }
    return std::string("no error");
  };
  EXPECT_EQ(where(2, {0, 0, 0, 0.5, 0.2, 1, 1, 1}), "[4]");
  EXPECT_EQ(where(1, {0, 0, 0, 1, 1}), "[2]");  // multiplicity 3 > degree + 1
  EXPECT_EQ(where(1, {0, 0, std::nan(""), 1}), "[2]");
  EXPECT_EQ(where(1, {0, 0, INFINITY, 1}), "[2]");
  EXPECT_THROW(KnotVector(0, {0, 1}), InvalidInput);
  EXPECT_THROW(KnotVector(2, {0, 0, 1, 1}), InvalidInput);        // too few knots
  EXPECT_THROW(KnotVector(1, {0, 1, 1, 1}), InvalidInput);        // multiplicity / empty domain
  EXPECT_THROW(KnotVector(2, {0, 0, 0, 0, 0, 0, 1}), InvalidInput);
}

// Marsden's identity with linear polynomials: the B-spline whose control points are the Greville
// abscissae is the identity map t -> t, for clamped and unclamped, uniform and repeated knots.
TEST(KnotVector, GrevilleAbscissaeReproduceTheIdentity) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 40; ++trial) {
    const int p = 1 + trial % 5;
    const KnotVector kv = test_support::random_knots(rng, p, 5, trial % 2 == 0, p);
    const std::vector<double> g = kv.greville_abscissae();
    ASSERT_EQ(static_cast<int>(g.size()), kv.num_basis());
    EXPECT_TRUE(std::is_sorted(g.begin(), g.end()));
    std::uniform_real_distribution<double> u(kv.domain_min(), kv.domain_max());
    std::vector<double> N(static_cast<std::size_t>(p + 1));
    for (int n = 0; n < 50; ++n) {
      const double t = n == 0 ? kv.domain_min() : n == 1 ? kv.domain_max() : u(rng);
      const int span = kv.find_span(t);
      kv.basis(span, t, N.data());
      double x = 0;
      for (int r = 0; r <= p; ++r) x += N[static_cast<std::size_t>(r)] * g[static_cast<std::size_t>(span - p + r)];
      EXPECT_NEAR(x, t, 1e-14 * (1 + std::abs(t))) << "trial " << trial;
    }
  }
  // On a Bézier segment they are i / p (Lasser 1994, eq. 11).
  const auto bezier = KnotVector::bezier(3).greville_abscissae();
  EXPECT_EQ(bezier, (std::vector<double>{0.0, 1.0 / 3, 2.0 / 3, 1.0}));
}

TEST(KnotVector, FactoriesRejectBadDegreesAndSpans) {
  EXPECT_THROW(KnotVector::bezier(0), InvalidInput);
  EXPECT_THROW(KnotVector::bezier(-5), InvalidInput);
  EXPECT_THROW(KnotVector::uniform_clamped(-3, 2), InvalidInput);
  EXPECT_THROW(KnotVector::uniform_clamped(2, 0), InvalidInput);
  EXPECT_THROW(KnotVector::bezier(2, 1.0, 1.0), InvalidInput);
}

}  // namespace
}  // namespace volspline
