// The n-ary smooth minimum E[min_i(a_i + u_i)], u_i uniform on [−k/2, k/2] (implicit_scene.h):
// the binary formula for two values, symmetric, local, its derivatives are probabilities that
// sum to 1 and match finite differences, twice differentiable at ties and joins, and equal to an
// independent numerical integration of the expectation. A blend of three children does not
// depend on their order. Many nearly tied values (issue 16): the expected minimum of n tied
// uniforms for n = 1..1000, values of every spread against a long double integration of the
// defining product, n identical spheres blended to the analytic radius, unequal ones against
// the reference.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <numeric>
#include <random>

#include "volspline/analysis/mass_properties.h"  // gauss_legendre
#include "volspline/boxspline/implicit_scene.h"
#include "volspline/boxspline/lattice_field.h"

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

// ∫_{from}^1 Π_{i ≠ skip, τ_i < τ} (1 + τ_i − τ) dτ in long double, by Gauss–Legendre on each
// panel between breakpoints with enough points to be exact for the panel's degree: the defining
// formula evaluated directly, an independent reference for smooth_minimum's positive forms and
// quadrature.
long double reference_survival_integral(const std::vector<long double>& tau, std::size_t skip, long double from) {
  std::vector<long double> breaks;
  for (long double t : tau) breaks.push_back(std::min(t, 1.0L));
  breaks.push_back(1.0L);
  std::sort(breaks.begin(), breaks.end());
  const int q = static_cast<int>(tau.size()) / 2 + 2;
  std::vector<double> x(static_cast<std::size_t>(q)), w(static_cast<std::size_t>(q));
  gauss_legendre(q, x.data(), w.data());
  long double sum = 0;
  for (std::size_t r = 0; r + 1 < breaks.size(); ++r) {
    const long double lo = std::max(breaks[r], from), hi = breaks[r + 1];
    if (!(hi > lo)) continue;
    for (int i = 0; i < q; ++i) {
      const long double t = (lo + hi) / 2 + (hi - lo) / 2 * x[static_cast<std::size_t>(i)];
      long double product = 1;
      for (std::size_t j = 0; j < tau.size(); ++j)
        if (j != skip && tau[j] < t) product *= 1 - t + tau[j];
      sum += (hi - lo) / 2 * w[static_cast<std::size_t>(i)] * product;
    }
  }
  return sum;
}

// smooth_minimum and its derivatives from the reference.
long double reference_smooth_minimum(const std::vector<double>& a, double k, std::vector<long double>* derivatives) {
  const double least = *std::min_element(a.begin(), a.end());
  std::vector<long double> tau;
  for (double x : a) tau.push_back((static_cast<long double>(x) - least) / k);
  if (derivatives != nullptr) {
    derivatives->assign(a.size(), 0.0L);
    for (std::size_t j = 0; j < a.size(); ++j)
      if (tau[j] < 1) (*derivatives)[j] = reference_survival_integral(tau, j, tau[j]);
  }
  return least - k * (0.5L - reference_survival_integral(tau, a.size(), 0));
}

TEST(SmoothMinimum, ManyTiedValuesGiveTheExpectedMinimumOfNUniforms) {
  // E[min of n uniforms on [a − k/2, a + k/2]] = a − k/2 + k/(n + 1); each is the least with
  // probability 1/n. The monomial form lost everything from n ≈ 60 on.
  const double k = 0.3, a = 0.125;
  for (std::size_t n = 1; n <= 1000; ++n) {
    const std::vector<double> values(n, a);
    std::vector<double> d(n);
    const double v = smooth_minimum(values, k, d);
    EXPECT_NEAR(v, a - k / 2 + k / static_cast<double>(n + 1), 4e-16) << n;
    double sum = 0;
    for (double p : d) {
      EXPECT_NEAR(p, 1.0 / static_cast<double>(n), 1e-15) << n;
      sum += p;
    }
    EXPECT_NEAR(sum, 1.0, 1e-13) << n;
    EXPECT_NEAR(smooth_minimum(values, k), v, 4e-16) << n;  // without derivatives: maybe by the other method
  }
}

TEST(SmoothMinimum, ManyValuesAgreeWithAnIndependentIntegration) {
  // Spreads from nearly tied (1e-12 k) to beyond the radius (1.5 k: some values take no part);
  // sizes on both sides of the switch between the exact and the quadrature method.
  std::mt19937 rng(16);
  const double k = 0.4;
  for (const std::size_t n : {9, 17, 33, 65, 130, 300}) {
    for (const double spread : {1e-12, 1e-6, 1e-3, 0.1, 0.5, 1.5}) {
      if (n >= 65 && (spread == 1e-6 || spread == 0.1)) continue;  // the reference costs n^3 (n^4 with derivatives)
      std::uniform_real_distribution<double> u(0.0, spread * k);
      std::vector<double> a(n);
      for (double& x : a) x = -0.2 + u(rng);
      if (n % 2 == 1) a[n / 2] = a[n / 3];  // a tie
      const bool with_derivatives = n <= 65;
      std::vector<long double> reference_d;
      const long double reference = reference_smooth_minimum(a, k, with_derivatives ? &reference_d : nullptr);
      std::vector<double> d(n);
      EXPECT_NEAR(smooth_minimum(a, k), static_cast<double>(reference), 1e-15 * k) << n << " " << spread;
      EXPECT_NEAR(smooth_minimum(a, k, d), static_cast<double>(reference), 1e-15 * k) << n << " " << spread;
      EXPECT_NEAR(std::accumulate(d.begin(), d.end(), 0.0), 1.0, 1e-14) << n << " " << spread;
      if (with_derivatives) {
        for (std::size_t j = 0; j < n; ++j) EXPECT_NEAR(d[j], static_cast<double>(reference_d[j]), 1e-15) << n << " " << spread << " " << j;
      }
    }
  }
}

SceneNode sphere_node(double radius) {
  SceneNode node;
  node.primitive.kind = PrimitiveKind::Sphere;
  node.primitive.origin = Eigen::Vector3d::Zero();
  node.primitive.radius = radius;
  return node;
}

TEST(SmoothMinimum, IdenticalSpheresBlendToTheAnalyticRadius) {
  // n spheres of radius 0.5, f = |x|² − 1/4, blended with k = 0.3: every coefficient is the
  // same smooth minimum of n equal values, f − k/2 + k/(n + 1), and the spline reproduces the
  // quadratic, so the zero set is the sphere of radius √(0.4 − 0.3/(n + 1)) exactly.
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  for (const std::size_t n : {1, 2, 3, 7, 60, 100, 333, 1000}) {
    Scene scene;
    scene.spacing = 0.25;
    scene.root.operation = SceneOperation::Blend;
    scene.root.radius = 0.3;
    scene.root.children.assign(n, sphere_node(0.5));
    const LatticeField field = scene_field(scene);
    const double radius = std::sqrt(0.4 - 0.3 / static_cast<double>(n + 1));
    for (int i = 0; i < 20; ++i) {
      const Eigen::Vector3d direction = Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
      EXPECT_NEAR(field.value(radius * direction), 0.0, 1e-13) << n;
      EXPECT_NEAR(scene_value(scene.root, radius * direction), 0.0, 1e-15) << n;
      // The field is |x|² − radius², so its zero along the ray is the radius.
      EXPECT_NEAR(field.value(0.5 * radius * direction), -0.75 * radius * radius, 1e-13) << n;
    }
  }
}

TEST(SmoothMinimum, NearlyTiedSpheresOfUnequalRadiiAgreeWithTheReference) {
  // Concentric spheres whose radii differ by up to 1e-3: the blended value (200 spheres) and its
  // gradient (60 spheres: the reference's derivatives cost n^4) at random points against the long
  // double integration of the children's values.
  for (const std::size_t n : {200, 60}) {
    const bool gradient_too = n == 60;
    SceneNode root;
    root.operation = SceneOperation::Blend;
    root.radius = 0.3;
    for (std::size_t i = 0; i < n; ++i) root.children.push_back(sphere_node(0.5 * (1 + 1e-3 * static_cast<double>((i * 37) % n) / static_cast<double>(n))));
    std::mt19937 rng(8);
    std::uniform_real_distribution<double> u(-0.8, 0.8);
    for (int trial = 0; trial < 4; ++trial) {
      const Eigen::Vector3d x(u(rng), u(rng), u(rng));
      std::vector<double> values;
      std::vector<Eigen::Vector3d> gradients;
      for (const SceneNode& child : root.children) {
        Eigen::Vector3d g;
        values.push_back(child.primitive.value(x, &g));
        gradients.push_back(g);
      }
      std::vector<long double> p;
      const long double reference = reference_smooth_minimum(values, root.radius, gradient_too ? &p : nullptr);
      EXPECT_NEAR(scene_value(root, x), static_cast<double>(reference), 1e-15) << n;
      if (!gradient_too) continue;
      Eigen::Vector3d reference_gradient = Eigen::Vector3d::Zero();
      for (std::size_t i = 0; i < n; ++i) reference_gradient += static_cast<double>(p[i]) * gradients[i];
      Eigen::Vector3d gradient;
      EXPECT_NEAR(scene_value(root, x, &gradient), static_cast<double>(reference), 1e-15);
      EXPECT_LT((gradient - reference_gradient).norm(), 1e-14 * reference_gradient.norm());
    }
  }
}

}  // namespace
}  // namespace volspline
