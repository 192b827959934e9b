// The n-ary smooth minimum E[min_i(a_i + u_i)], u_i uniform on [−k/2, k/2] (implicit_scene.h):
// the binary formula for two values, symmetric, local, its derivatives are probabilities that
// sum to 1 and match finite differences, twice differentiable at ties and joins, and equal to an
// independent numerical integration of the expectation. A blend of three children does not
// depend on their order.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <numeric>
#include <random>

#include "volspline/boxspline/implicit_scene.h"

namespace volspline {
namespace {

double nary(std::vector<double> a, double k, std::vector<double>* derivatives = nullptr) {
  std::vector<double> d(a.size());
  const double v = smooth_minimum(a, k, d);
  if (derivatives != nullptr) *derivatives = d;
  return v;
}

TEST(SmoothMinimum, TwoValuesGiveTheBinaryFormula) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 2000; ++trial) {
    const double k = 0.05 + std::abs(u(rng));
    const double a = u(rng), b = a + 1.5 * k * u(rng);
    std::vector<double> d;
    EXPECT_NEAR(nary({a, b}, k, &d), smooth_minimum(a, b, k), 1e-15);
    const double e = 1e-7;
    EXPECT_NEAR(d[0], (smooth_minimum(a + e, b, k) - smooth_minimum(a - e, b, k)) / (2 * e), 1e-7);
    EXPECT_NEAR(d[1], (smooth_minimum(a, b + e, k) - smooth_minimum(a, b - e, k)) / (2 * e), 1e-7);
  }
}

TEST(SmoothMinimum, SymmetricLocalAndDerivativesAreProbabilities) {
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double k = 0.4;
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<double> a(4);
    for (double& x : a) x = 0.7 * u(rng);  // mostly within k of each other
    if (trial % 5 == 0) a[1] = a[2] = a[0];  // ties
    std::vector<double> d;
    const double v = nary(a, k, &d);
    EXPECT_LE(v, *std::min_element(a.begin(), a.end()));
    EXPECT_NEAR(std::accumulate(d.begin(), d.end(), 0.0), 1.0, 1e-14);
    for (double p : d) EXPECT_GE(p, -1e-15);
    // Every permutation gives the same value and permuted derivatives.
    std::vector<int> order{0, 1, 2, 3};
    do {
      std::vector<double> b(4), db;
      for (int i = 0; i < 4; ++i) b[static_cast<std::size_t>(i)] = a[static_cast<std::size_t>(order[static_cast<std::size_t>(i)])];
      EXPECT_NEAR(nary(b, k, &db), v, 1e-15);
      for (int i = 0; i < 4; ++i) EXPECT_NEAR(db[static_cast<std::size_t>(i)], d[static_cast<std::size_t>(order[static_cast<std::size_t>(i)])], 1e-14);
    } while (std::next_permutation(order.begin(), order.end()));
    // Derivatives against central differences.
    for (std::size_t i = 0; i < 4; ++i) {
      const double e = 1e-7;
      std::vector<double> plus = a, minus = a;
      plus[i] += e, minus[i] -= e;
      EXPECT_NEAR(d[i], (nary(plus, k) - nary(minus, k)) / (2 * e), 1e-6);
    }
  }
  // Local: nothing within k of the least value means the minimum itself.
  std::vector<double> d;
  EXPECT_EQ(nary({0.3, 0.3 + 1.001 * k, 1.0, 0.3 + 2 * k}, k, &d), 0.3);
  EXPECT_EQ(d, (std::vector<double>{1.0, 0.0, 0.0, 0.0}));
}

TEST(SmoothMinimum, EqualsTheExpectationOfTheShiftedMinimum) {
  // Independent computation: the midpoint rule on the cube of shifts (min is piecewise linear,
  // so the rule converges at second order).
  const double k = 0.5;
  const int n = 160;
  for (const std::vector<double>& a : {std::vector<double>{0.0, 0.1, 0.3}, std::vector<double>{0.2, 0.2, 0.2}, std::vector<double>{0.0, 0.45, 0.2}}) {
    double sum = 0.0;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        for (int l = 0; l < n; ++l) {
          const auto shift = [&](int q) { return k * ((q + 0.5) / n - 0.5); };
          sum += std::min({a[0] + shift(i), a[1] + shift(j), a[2] + shift(l)});
        }
    EXPECT_NEAR(nary(a, k), sum / (static_cast<double>(n) * n * n), 2e-5);
  }
}

TEST(SmoothMinimum, TwiceDifferentiableAtTiesAndJoins) {
  // One-sided second differences along random directions agree where three values tie, where
  // two tie with a third within k, and where a value is exactly k above the least.
  const double k = 0.5, e = 1e-4;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const std::vector<double>& a : {std::vector<double>{0.0, 0.0, 0.0}, std::vector<double>{0.0, 0.0, 0.3},
                                       std::vector<double>{0.0, 0.2, 0.5}, std::vector<double>{0.1, 0.1, 0.6}}) {
    for (int trial = 0; trial < 20; ++trial) {
      std::vector<double> v{u(rng), u(rng), u(rng)};
      const auto f = [&](double t) {
        std::vector<double> x = a;
        for (std::size_t i = 0; i < 3; ++i) x[i] += t * v[i];
        return nary(x, k);
      };
      const double left = (f(0) - 2 * f(-e) + f(-2 * e)) / (e * e), right = (f(2 * e) - 2 * f(e) + f(0)) / (e * e);
      EXPECT_NEAR(left, right, 2e-2) << a[0] << " " << a[1] << " " << a[2];
    }
  }
}

TEST(SmoothMinimum, BlendOfThreeChildrenDoesNotDependOnTheirOrder) {
  std::vector<SceneNode> children(3);
  const Eigen::Vector3d centres[3] = {{-0.3, 0.0, 0.0}, {0.3, 0.05, 0.0}, {0.0, 0.35, 0.1}};
  for (int i = 0; i < 3; ++i) {
    children[static_cast<std::size_t>(i)].primitive.kind = PrimitiveKind::Sphere;
    children[static_cast<std::size_t>(i)].primitive.origin = centres[i];
    children[static_cast<std::size_t>(i)].primitive.radius = 0.35;
  }
  Scene scene;
  scene.spacing = 0.2;
  scene.root.operation = SceneOperation::Blend;
  scene.root.radius = 0.3;
  scene.root.children = children;
  const LatticeField reference = scene_field(scene);
  std::vector<int> order{0, 1, 2};
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-0.9, 0.9);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 50; ++i) points.emplace_back(u(rng), u(rng), u(rng));
  while (std::next_permutation(order.begin(), order.end())) {
    Scene permuted = scene;
    for (int i = 0; i < 3; ++i) permuted.root.children[static_cast<std::size_t>(i)] = children[static_cast<std::size_t>(order[static_cast<std::size_t>(i)])];
    const LatticeField field = scene_field(permuted);
    for (std::size_t j = 0; j < field.coefficients.size(); ++j) EXPECT_NEAR(field.coefficients[j], reference.coefficients[j], 1e-15);
    for (const Eigen::Vector3d& x : points) {
      Eigen::Vector3d g0, g1;
      EXPECT_NEAR(scene_value(permuted.root, x, &g1), scene_value(scene.root, x, &g0), 1e-15);
      EXPECT_LT((g1 - g0).norm(), 1e-14);
    }
  }
}

}  // namespace
}  // namespace volspline
