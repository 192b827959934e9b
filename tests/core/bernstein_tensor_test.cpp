#include "volspline/core/bernstein_tensor.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <Eigen/Dense>

#include "volspline/core/error.h"

namespace volspline {
namespace {

template <int D>
BernsteinTensor<D> random_tensor(std::mt19937& rng, std::array<int, D> degrees, int components = 1) {
  BernsteinTensor<D> f(degrees, components);
  std::uniform_real_distribution<double> c(-1, 1);
  for (double& x : f.coefficients) x = c(rng);
  return f;
}

template <int D>
std::array<double, D> random_parameter(std::mt19937& rng) {
  std::uniform_real_distribution<double> t(0, 1);
  std::array<double, D> s{};
  for (double& x : s) x = t(rng);
  return s;
}

// B_i^n(x) from its definition C(n, i) x^i (1 - x)^(n - i), independently of de Casteljau.
double basis(int n, int i, double x) {
  return std::tgamma(n + 1) / (std::tgamma(i + 1) * std::tgamma(n - i + 1)) * std::pow(x, i) * std::pow(1 - x, n - i);
}

// Direct sum of c_a B_a(s), component `component`: an independent evaluation.
template <int D>
double evaluate_by_basis(const BernsteinTensor<D>& f, const BernsteinPoint<D>& s, int component = 0) {
  double sum = 0;
  for (std::size_t l = 0; l < f.count(); ++l) {
    const auto a = f.multi_index(l);
    double b = f.coefficients[l * static_cast<std::size_t>(f.components) + static_cast<std::size_t>(component)];
    for (int d = 0; d < D; ++d) {
      b *= basis(f.degrees[static_cast<std::size_t>(d)], a[static_cast<std::size_t>(d)], s[static_cast<std::size_t>(d)]);
    }
    sum += b;
  }
  return sum;
}

template <int D>
std::vector<double> values(const BernsteinTensor<D>& f, const BernsteinPoint<D>& s) {
  std::vector<double> v(static_cast<std::size_t>(f.components));
  bernstein_evaluate(f, s, v.data());
  return v;
}

// Degrees 1..4 in turn, so each dimension meets several.
template <int D>
std::array<int, D> some_degrees(int offset) {
  std::array<int, D> d{};
  for (int i = 0; i < D; ++i) d[static_cast<std::size_t>(i)] = 1 + (i + offset) % 4;
  return d;
}

// ---- the trivariate scalar tests, as before the generalisation ----

TEST(BernsteinTensor, DeCasteljauMatchesTheBasisSum) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> t(0, 1);
  const auto f = random_tensor<3>(rng, {3, 5, 2});
  for (int n = 0; n < 50; ++n) {
    const std::array<double, 3> s{t(rng), t(rng), t(rng)};
    EXPECT_NEAR(bernstein_evaluate(f, s), evaluate_by_basis(f, s), 1e-13);
  }
}

TEST(BernsteinTensor, SplitPiecesReproduceThePolynomial) {
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> t(0, 1);
  const auto f = random_tensor<3>(rng, {4, 2, 3});
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

TEST(BernsteinTensor, SplitIntoCallerTensorsReusesTheirStorage) {
  // The same halves as the returning form, bit for bit, written into tensors of any earlier
  // shape; once they are large enough no new storage is taken.
  std::mt19937 rng(12);
  const auto f = random_tensor<4>(rng, {2, 1, 3, 1}, 4);
  BernsteinTensor<4> left = random_tensor<4>(rng, {3, 3, 3, 3}, 4), right = left;
  const double* left_storage = left.coefficients.data();
  const double* right_storage = right.coefficients.data();
  for (int d = 0; d < 4; ++d) {
    bernstein_split(f, d, 0.5, left, right);
    const auto [expected_left, expected_right] = bernstein_split(f, d, 0.5);
    EXPECT_EQ(left.degrees, expected_left.degrees);
    EXPECT_EQ(left.components, 4);
    EXPECT_EQ(left.coefficients, expected_left.coefficients);
    EXPECT_EQ(right.coefficients, expected_right.coefficients);
    EXPECT_EQ(left.coefficients.data(), left_storage);
    EXPECT_EQ(right.coefficients.data(), right_storage);
  }
  EXPECT_THROW(bernstein_split(f, 0, 0.5, left, left), InvalidInput);
}

TEST(BernsteinTensor, ProductAndElevationAreExactIdentities) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> t(0, 1);
  const auto f = random_tensor<3>(rng, {2, 3, 1}), g = random_tensor<3>(rng, {3, 1, 2});
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
  const auto f = random_tensor<3>(rng, {3, 4, 2});
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
  const auto f = random_tensor<3>(rng, {3, 3, 3});
  const auto [lo, hi] = bernstein_coefficient_range(f);
  for (int n = 0; n < 200; ++n) {
    const double v = bernstein_evaluate(f, {t(rng), t(rng), t(rng)});
    EXPECT_GE(v, lo);
    EXPECT_LE(v, hi);
  }
  EXPECT_DOUBLE_EQ(bernstein_evaluate(f, {1, 0, 1}), f.at(3, 0, 3));
}

// ---- identities for every number of variables and vector-valued coefficients ----

using Dimensions = ::testing::Types<std::integral_constant<int, 1>, std::integral_constant<int, 2>,
                                    std::integral_constant<int, 3>, std::integral_constant<int, 4>>;
template <class T>
class BernsteinInDimension : public ::testing::Test {
 public:
  static constexpr int D = T::value;
};
TYPED_TEST_SUITE(BernsteinInDimension, Dimensions);

TYPED_TEST(BernsteinInDimension, DeCasteljauIsTheBasisSumAndOneIsAPartitionOfUnity) {
  constexpr int D = TestFixture::D;
  std::mt19937 rng(10 + D);
  const auto f = random_tensor<D>(rng, some_degrees<D>(0), 3);
  BernsteinTensor<D> one(some_degrees<D>(1));
  std::fill(one.coefficients.begin(), one.coefficients.end(), 1.0);
  for (int n = 0; n < 20; ++n) {
    const auto s = random_parameter<D>(rng);
    const auto v = values(f, s);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(v[static_cast<std::size_t>(c)], evaluate_by_basis(f, s, c), 1e-13);
    EXPECT_NEAR(bernstein_evaluate(one, s), 1.0, 1e-14);
    EXPECT_NEAR(evaluate_by_basis(one, s), 1.0, 1e-13);
  }
}

TYPED_TEST(BernsteinInDimension, ProductIsThePointwiseProduct) {
  constexpr int D = TestFixture::D;
  std::mt19937 rng(20 + D);
  const auto scalar = random_tensor<D>(rng, some_degrees<D>(0));
  const auto vector = random_tensor<D>(rng, some_degrees<D>(2), 3);
  const auto other = random_tensor<D>(rng, some_degrees<D>(1), 3);
  const auto scaled = bernstein_product(scalar, vector), swapped = bernstein_product(vector, scalar);
  const auto componentwise = bernstein_product(vector, other);
  EXPECT_EQ(scaled.degrees, product_degrees(scalar.degrees, vector.degrees));
  EXPECT_EQ(scaled.components, 3);
  EXPECT_EQ(componentwise.components, 3);
  for (int n = 0; n < 20; ++n) {
    const auto s = random_parameter<D>(rng);
    const double a = bernstein_evaluate(scalar, s);
    const auto v = values(vector, s), w = values(other, s);
    const auto p = values(scaled, s), q = values(swapped, s), r = values(componentwise, s);
    for (std::size_t c = 0; c < 3; ++c) {
      EXPECT_NEAR(p[c], a * v[c], 1e-12);
      EXPECT_NEAR(q[c], a * v[c], 1e-12);
      EXPECT_NEAR(r[c], v[c] * w[c], 1e-12);
    }
  }
  EXPECT_THROW(bernstein_product(vector, random_tensor<D>(rng, some_degrees<D>(0), 2)), InvalidInput);
}

TYPED_TEST(BernsteinInDimension, PowerIsRepeatedProduct) {
  constexpr int D = TestFixture::D;
  std::mt19937 rng(25 + D);
  const auto f = random_tensor<D>(rng, some_degrees<D>(3));
  const auto cube = bernstein_power(f, 3);
  for (int n = 0; n < 10; ++n) {
    const auto s = random_parameter<D>(rng);
    EXPECT_NEAR(bernstein_evaluate(cube, s), std::pow(bernstein_evaluate(f, s), 3), 1e-12);
    EXPECT_DOUBLE_EQ(bernstein_evaluate(bernstein_power(f, 0), s), 1.0);
  }
}

TYPED_TEST(BernsteinInDimension, ElevationAndSplitLeaveValuesUnchanged) {
  constexpr int D = TestFixture::D;
  std::mt19937 rng(30 + D);
  const auto f = random_tensor<D>(rng, some_degrees<D>(1), 2);
  std::array<int, D> higher = f.degrees;
  for (int& x : higher) x += 2;
  const auto e = bernstein_elevate(f, higher);
  EXPECT_EQ(e.degrees, higher);
  for (int d = 0; d < D; ++d) {
    const double at = 0.2 + 0.15 * d;
    const auto [left, right] = bernstein_split(f, d, at);
    for (int n = 0; n < 10; ++n) {
      const auto s = random_parameter<D>(rng);
      const auto fs = values(f, s), es = values(e, s);
      auto inner = s, outer = s;
      inner[static_cast<std::size_t>(d)] = at * s[static_cast<std::size_t>(d)];
      outer[static_cast<std::size_t>(d)] = at + (1 - at) * s[static_cast<std::size_t>(d)];
      const auto l = values(left, s), r = values(right, s), fl = values(f, inner), fr = values(f, outer);
      for (std::size_t c = 0; c < 2; ++c) {
        EXPECT_NEAR(es[c], fs[c], 1e-13);
        EXPECT_NEAR(l[c], fl[c], 1e-13);
        EXPECT_NEAR(r[c], fr[c], 1e-13);
      }
    }
  }
}

TYPED_TEST(BernsteinInDimension, DerivativeIsTheAnalyticDerivative) {
  constexpr int D = TestFixture::D;
  std::mt19937 rng(40 + D);
  const auto f = random_tensor<D>(rng, some_degrees<D>(2), 2);
  for (int d = 0; d < D; ++d) {
    const auto g = bernstein_derivative(f, d);
    const auto global = bernstein_derivative(f, d, 0.25);  // a parameter over an interval of length 1/4
    const auto [lo, hi] = bernstein_derivative_range(f, d, 1);
    EXPECT_EQ(bernstein_coefficient_range(bernstein_components(g, 1)), std::make_pair(lo, hi));
    for (int n = 0; n < 10; ++n) {
      const auto s = random_parameter<D>(rng);
      // d/dx B_i^n = n (B_{i-1}^{n-1} - B_i^{n-1}) summed by hand, an independent derivative.
      for (int c = 0; c < 2; ++c) {
        double exact = 0;
        for (std::size_t l = 0; l < f.count(); ++l) {
          const auto a = f.multi_index(l);
          double b = f.coefficients[l * 2 + static_cast<std::size_t>(c)];
          for (int e = 0; e < D; ++e) {
            const int m = f.degrees[static_cast<std::size_t>(e)], i = a[static_cast<std::size_t>(e)];
            const double x = s[static_cast<std::size_t>(e)];
            b *= e != d ? basis(m, i, x) : m * ((i > 0 ? basis(m - 1, i - 1, x) : 0.0) - (i < m ? basis(m - 1, i, x) : 0.0));
          }
          exact += b;
        }
        EXPECT_NEAR(values(g, s)[static_cast<std::size_t>(c)], exact, 1e-12);
        EXPECT_NEAR(values(global, s)[static_cast<std::size_t>(c)], 4 * exact, 4e-12);
      }
      auto plus = s, minus = s;
      plus[static_cast<std::size_t>(d)] += 1e-6;
      minus[static_cast<std::size_t>(d)] -= 1e-6;
      EXPECT_NEAR(values(g, s)[0], (values(f, plus)[0] - values(f, minus)[0]) / 2e-6, 1e-7);
    }
  }
}

TYPED_TEST(BernsteinInDimension, CoefficientBoundsEncloseSampledValues) {
  constexpr int D = TestFixture::D;
  std::mt19937 rng(50 + D);
  const auto f = random_tensor<D>(rng, some_degrees<D>(3), 3);
  const double largest = bernstein_max_abs(f);
  for (int n = 0; n < 100; ++n) {
    const auto v = values(f, random_parameter<D>(rng));
    for (int c = 0; c < 3; ++c) {
      const auto [lo, hi] = bernstein_coefficient_range(f, c);
      EXPECT_GE(v[static_cast<std::size_t>(c)], lo);
      EXPECT_LE(v[static_cast<std::size_t>(c)], hi);
      EXPECT_LE(std::abs(v[static_cast<std::size_t>(c)]), largest);
    }
  }
  EXPECT_THROW(bernstein_coefficient_range(f, 3), InvalidInput);
}

TYPED_TEST(BernsteinInDimension, ScaledConvolutionIsTheProduct) {
  constexpr int D = TestFixture::D;
  std::mt19937 rng(60 + D);
  const auto f = random_tensor<D>(rng, some_degrees<D>(0)), g = random_tensor<D>(rng, some_degrees<D>(1));
  // f g - g f accumulated in the scaled basis is zero; f g alone is the product.
  ScaledBernsteinTensor<D> sum(product_degrees(f.degrees, g.degrees));
  scaled_product_add(bernstein_scaled(f), bernstein_scaled(g), 1.0, sum);
  const auto product = bernstein_unscaled(sum);
  scaled_product_add(bernstein_scaled(g), bernstein_scaled(f), -1.0, sum);
  EXPECT_LE(bernstein_max_abs(bernstein_unscaled(sum)), 1e-14);
  for (int n = 0; n < 10; ++n) {
    const auto s = random_parameter<D>(rng);
    EXPECT_NEAR(bernstein_evaluate(product, s), bernstein_evaluate(f, s) * bernstein_evaluate(g, s), 1e-12);
  }
  ScaledBernsteinTensor<D> wrong(f.degrees);
  EXPECT_THROW(scaled_product_add(bernstein_scaled(f), bernstein_scaled(g), 1.0, wrong), InvalidInput);
}

template <int D>
void check_faces(std::mt19937& rng) {
  const auto f = random_tensor<D>(rng, some_degrees<D>(1), 2);
  for (int d = 0; d < D; ++d) {
    for (int side = 0; side < 2; ++side) {
      const BernsteinTensor<D - 1> face = bernstein_face(f, d, side);
      for (int n = 0; n < 10; ++n) {
        const auto t = random_parameter<D - 1>(rng);
        std::array<double, D> s{};
        for (int e = 0, k = 0; e < D; ++e) s[static_cast<std::size_t>(e)] = e == d ? side : t[static_cast<std::size_t>(k++)];
        const auto on_face = values(face, t), full = values(f, s);
        for (std::size_t c = 0; c < 2; ++c) EXPECT_NEAR(on_face[c], full[c], 1e-13);
      }
    }
  }
  EXPECT_THROW(bernstein_face(f, D, 0), InvalidInput);
  EXPECT_THROW(bernstein_face(f, 0, 2), InvalidInput);
}

TEST(BernsteinTensor, FaceRestrictionIsEvaluationOnTheFace) {
  std::mt19937 rng(70);
  check_faces<2>(rng);
  check_faces<3>(rng);
  check_faces<4>(rng);
}

// f = x_d q (or (1 - x_d) q) for a random q: dividing by that face's factor gives q back, and
// the quotient's values are f's divided by the factor, in the open box.
TEST(BernsteinTensor, DivisionByAFaceFactorUndoesTheProduct) {
  std::mt19937 rng(31);
  const BernsteinTensor<3> q = random_tensor<3>(rng, {2, 3, 1}, 2);
  for (int d = 0; d < 3; ++d) {
    for (int side = 0; side < 2; ++side) {
      std::array<int, 3> linear_degrees{0, 0, 0};
      linear_degrees[static_cast<std::size_t>(d)] = 1;
      BernsteinTensor<3> factor(linear_degrees, 1);
      factor.coefficients = side == 0 ? std::vector<double>{0.0, 1.0} : std::vector<double>{1.0, 0.0};
      const BernsteinTensor<3> f = bernstein_product(q, factor);
      const BernsteinTensor<3> back = bernstein_divide_by_face(f, d, side);
      ASSERT_EQ(back.degrees, q.degrees);
      ASSERT_EQ(back.components, 2);
      for (std::size_t i = 0; i < q.coefficients.size(); ++i) EXPECT_NEAR(back.coefficients[i], q.coefficients[i], 1e-14);
      for (int trial = 0; trial < 10; ++trial) {
        const auto s = random_parameter<3>(rng);
        const double x = s[static_cast<std::size_t>(d)], l = side == 0 ? x : 1 - x;
        for (int c = 0; c < 2; ++c) EXPECT_NEAR(evaluate_by_basis(back, s, c) * l, evaluate_by_basis(f, s, c), 1e-13);
      }
    }
  }
  BernsteinTensor<3> constant({0, 1, 1}, 1);
  EXPECT_THROW(bernstein_divide_by_face(constant, 0, 0), InvalidInput);
  EXPECT_THROW(bernstein_divide_by_face(q, 3, 0), InvalidInput);
  EXPECT_THROW(bernstein_divide_by_face(q, 0, 2), InvalidInput);
}

TEST(BernsteinTensor, BlossomOnTheDiagonalIsTheValueAndIsSymmetric) {
  std::mt19937 rng(71);
  const auto f = random_tensor<1>(rng, {4}, 2);
  const double diagonal[4] = {0.3, 0.3, 0.3, 0.3}, args[4] = {0.1, 0.7, 0.4, 0.9}, permuted[4] = {0.9, 0.4, 0.1, 0.7};
  double b[2], v[2], p[2];
  bernstein_blossom(f, diagonal, b);
  bernstein_evaluate(f, {0.3}, v);
  bernstein_blossom(f, args, p);
  double q[2];
  bernstein_blossom(f, permuted, q);
  for (int c = 0; c < 2; ++c) {
    EXPECT_NEAR(b[c], v[c], 1e-14);
    EXPECT_NEAR(p[c], q[c], 1e-14);
  }
  // At the arguments (0, ..., 0, 1, ..., 1) the blossom is a Bernstein coefficient.
  const double corner[4] = {0, 0, 1, 1};
  bernstein_blossom(f, corner, b);
  EXPECT_DOUBLE_EQ(b[0], f.at({2}, 0));
}

TEST(BernsteinTensor, InvalidArgumentsThrow) {
  EXPECT_THROW(BernsteinTensor<2>({1, -1}), InvalidInput);
  EXPECT_THROW(BernsteinTensor<2>({1, 1}, 0), InvalidInput);
  const BernsteinTensor<2> f({2, 2}, 2);
  EXPECT_THROW(bernstein_split(f, 2), InvalidInput);
  EXPECT_THROW(bernstein_derivative(f, -1), InvalidInput);
  EXPECT_THROW(bernstein_evaluate(f, {0.5, 0.5}), InvalidInput);  // two components, no single value
  EXPECT_THROW(bernstein_elevate(f, {1, 2}), InvalidInput);
  EXPECT_THROW(bernstein_components(f, 1, 2), InvalidInput);
  EXPECT_THROW(bernstein_power(f, 2), InvalidInput);
  BernsteinTensor<2> g({2, 1}, 2);
  EXPECT_THROW(bernstein_add(g, f), InvalidInput);
}

// The 4-variate sub-Jacobians a sweep of a solid needs: for s(u, v, w, t) into R^3 the 3 x 3
// minors of the 3 x 4 Jacobian, here det[s_u s_v s_t], from derivatives and products only.
TEST(BernsteinTensor, FourVariateJacobianMinorFromDerivativesAndProducts) {
  std::mt19937 rng(80);
  const auto s = random_tensor<4>(rng, {2, 1, 2, 3}, 3);
  std::array<std::array<BernsteinTensor<4>, 3>, 3> columns;  // columns[k][c]: component c of s along direction k
  const std::array<int, 3> directions{0, 1, 3};
  for (std::size_t k = 0; k < 3; ++k) {
    const auto derivative = bernstein_derivative(s, directions[k]);
    for (int c = 0; c < 3; ++c) columns[k][static_cast<std::size_t>(c)] = bernstein_components(derivative, c);
  }
  // det = sum over cyclic (a, b, c) of x_a (y_b z_c - y_c z_b), with columns x = s_u, y = s_v, z = s_t.
  BernsteinTensor<4> minor;
  for (std::size_t a = 0; a < 3; ++a) {
    const std::size_t b = (a + 1) % 3, c = (a + 2) % 3;
    auto cross = bernstein_product(columns[1][b], columns[2][c]);
    auto other = bernstein_product(columns[1][c], columns[2][b]);
    for (double& x : other.coefficients) x = -x;
    bernstein_add(cross, other);
    auto term = bernstein_product(columns[0][a], cross);
    if (a == 0) minor = std::move(term); else bernstein_add(minor, term);
  }
  EXPECT_EQ(minor.degrees, (std::array<int, 4>{5, 2, 6, 8}));
  for (int n = 0; n < 20; ++n) {
    const auto p = random_parameter<4>(rng);
    // Direct: the determinant of the derivative vectors at p (each from its own tensor).
    Eigen::Matrix3d direct;
    for (std::size_t k = 0; k < 3; ++k) {
      for (std::size_t c = 0; c < 3; ++c) direct(static_cast<Eigen::Index>(c), static_cast<Eigen::Index>(k)) = bernstein_evaluate(columns[k][c], p);
    }
    EXPECT_NEAR(bernstein_evaluate(minor, p), direct.determinant(), 1e-12 * (1 + std::abs(direct.determinant())));
    Eigen::Matrix3d jacobian;
    const double h = 1e-6;
    for (int k = 0; k < 3; ++k) {
      auto plus = p, minus = p;
      plus[static_cast<std::size_t>(directions[static_cast<std::size_t>(k)])] += h;
      minus[static_cast<std::size_t>(directions[static_cast<std::size_t>(k)])] -= h;
      const auto fp = values(s, plus), fm = values(s, minus);
      for (int c = 0; c < 3; ++c) jacobian(c, k) = (fp[static_cast<std::size_t>(c)] - fm[static_cast<std::size_t>(c)]) / (2 * h);
    }
    EXPECT_NEAR(bernstein_evaluate(minor, p), jacobian.determinant(), 1e-7 * (1 + std::abs(jacobian.determinant())));
  }
}

}  // namespace
}  // namespace volspline
