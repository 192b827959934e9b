#include "volspline/analysis/sub_jacobians.h"

#include <gtest/gtest.h>

#include <random>

#include "support/test_splines.h"
#include "support/translated_generators.h"
#include "volspline/core/error.h"
#include "volspline/spline/bezier_extraction.h"

namespace volspline {
namespace {

std::array<double, 4> local(const BSplineHypervolume& cell, const std::array<double, 4>& t) {
  std::array<double, 4> s{};
  for (int d = 0; d < 4; ++d) {
    s[static_cast<std::size_t>(d)] = (t[static_cast<std::size_t>(d)] - cell.domain_min(d)) / (cell.domain_max(d) - cell.domain_min(d));
  }
  return s;
}

// The Bernstein polynomials of the four, evaluated, against the determinants of the evaluated
// partials (for a rational map: numerators over w^4), on pieces of random B-splines.
void expect_coefficients_reproduce_determinants(bool rational) {
  std::mt19937 rng(rational ? 23 : 17);
  for (int trial = 0; trial < 3; ++trial) {
    const auto map = test_support::random_spline<4>(rng, {1 + trial % 2, 2, 1 + (trial + 1) % 2, 1 + trial % 2}, 2, 3, rational);
    const auto pieces = bezier_pieces(map);
    for (std::size_t p = 0; p < pieces.size(); p += 5) {
      const auto& cell = pieces[p];
      const SubJacobiansBernstein j = sub_jacobian_coefficients(cell);
      EXPECT_EQ(j.homogeneous, rational);
      BernsteinTensor<4> weight;
      if (rational) {
        BernsteinTensor<4> h;
        h.degrees = cell.degrees();
        h.components = 4;
        h.coefficients = cell.homogeneous();
        weight = bernstein_components(h, 3);
      }
      const double scale = bernstein_max_abs(j.minors);
      for (int sample = 0; sample < 4; ++sample) {
        const auto t = test_support::random_parameter(rng, cell);
        const auto expected = sub_jacobians_at(map, t);
        double values[4];
        bernstein_evaluate(j.minors, local(cell, t), values);
        const double w4 = rational ? std::pow(bernstein_evaluate(weight, local(cell, t)), 4) : 1.0;
        for (int k = 0; k < 4; ++k) {
          EXPECT_NEAR(values[k], expected[static_cast<std::size_t>(k)] * w4, 1e-12 * scale) << "minor " << k;
        }
      }
    }
  }
}

TEST(SubJacobians, PolynomialCoefficientsReproduceTheDeterminantsOfThePartials) {
  expect_coefficients_reproduce_determinants(false);
}

TEST(SubJacobians, RationalNumeratorsReproduceTheDeterminantsOfThePartials) {
  expect_coefficients_reproduce_determinants(true);
}

TEST(SubJacobians, TheFourShareOneCommonDegree) {
  // Degree (p, q, r, m) = (1, 2, 2, 1): J234 has degree 3p in u, J123 degree 3m in t.
  const auto map = test_support::translated_generator({{1.0, 0, 0, 2}, {1.0, 1, 2, 0}}, {1, 2, 2}, {1, 1, 0.5});
  const auto j = sub_jacobian_coefficients(map);
  EXPECT_EQ(j.minors.degrees, (std::array<int, 4>{3, 6, 6, 3}));
  EXPECT_EQ(j.minors.components, 4);
}

TEST(SubJacobians, SignCertificateForAStrictSignAndHullForASeparatedSet) {
  BernsteinTensor<4> minors({1, 0, 0, 0}, 4);
  // J123 and J124 both change sign, but J123 + J124 > 0 on both coefficient vectors.
  minors.coefficients = {1.0, -0.5, 0, 0, -0.5, 1.0, 0, 0};
  EXPECT_EQ(bernstein_rank_certificate(minors, {1e-12, 1e-12, 1e-12, 1e-12}), RankCertificate::Hull);
  minors.coefficients = {1.0, 0.5, 0, 0, 0.5, -1.0, 0, 0};
  EXPECT_EQ(bernstein_rank_certificate(minors, {1e-12, 1e-12, 1e-12, 1e-12}), RankCertificate::Sign);
  // The origin between two coefficient vectors: no certificate can exist.
  minors.coefficients = {1.0, 0.5, 0, 0, -1.0, -0.5, 0, 0};
  EXPECT_EQ(bernstein_rank_certificate(minors, {1e-12, 1e-12, 1e-12, 1e-12}), RankCertificate::None);
  // A coefficient inside the margin is not a strict sign; of J123 it is a weak one: no fold.
  minors.coefficients = {1.0, 0, 0, 0, 1e-13, 0, 0, 0};
  EXPECT_EQ(bernstein_rank_certificate(minors, {1e-12, 1e-12, 1e-12, 1e-12}), RankCertificate::NoFold);
  minors.coefficients = {1.0, 0, 0, 0, -1e-13, 0, 0, 0};
  EXPECT_EQ(bernstein_rank_certificate(minors, {1e-12, 1e-12, 1e-12, 1e-12}), RankCertificate::NoFold);
  // Of another minor it is no sign at all: J123 changes sign, J124 is 1 and 1e-13, and the
  // separating direction found proves it by the hull.
  minors.coefficients = {1.0, 1.0, 0, 0, -1.0, 1e-13, 0, 0};
  EXPECT_EQ(bernstein_rank_certificate(minors, {1e-12, 1e-12, 1e-12, 1e-12}), RankCertificate::Hull);
  // A coefficient vector zero to the margins (the minors' value at a point where all four
  // vanish) leaves no proof, however well the others are separated: x . c <= sum |x_k| margin_k.
  // Every minor changes sign across the three vectors; (1, 1, 1, 0) separates them.
  BernsteinTensor<4> three({2, 0, 0, 0}, 4);
  three.coefficients = {1.0, 1.0, -1.0, 0, 1.0, -1.0, 1.0, 0, -1.0, 0.5, 2.0, 0};
  EXPECT_EQ(bernstein_rank_certificate(three, {1e-12, 1e-12, 1e-12, 1e-12}), RankCertificate::Hull);
  three.coefficients = {1.0, 1.0, -1.0, 0, 1e-13, -1e-13, 1e-13, 0, -1.0, 0.5, 2.0, 0};
  EXPECT_EQ(bernstein_rank_certificate(three, {1e-12, 1e-12, 1e-12, 1e-12}), RankCertificate::None);
  // Beyond the margin in one component it can be proved again: (1.5, -0.01, 1, 0) . c > 0.
  three.coefficients = {1.0, 1.0, -1.0, 0, 1e-13, -2e-9, 1e-13, 0, -1.0, 0.5, 2.0, 0};
  EXPECT_EQ(bernstein_rank_certificate(three, {1e-12, 1e-12, 1e-12, 1e-12}), RankCertificate::Hull);
}

// Coefficient 4-vectors all within a thin slab on the positive side of a hidden hyperplane
// d* . c = 0 (d* . c_i between 0.01 and 0.02 of |c_i|), spread widely within it: their hull
// misses the origin, yet neither their mean direction nor a few perceptron steps need separate
// them. The hull certificate must find a direction for every such set. The same sets with one
// more vector, minus a positive combination of the others, contain the origin in their hull:
// no certificate may be given for them.
TEST(SubJacobians, HullCertificateIsFoundWheneverTheHullMissesTheOriginAndNeverWhenItHoldsIt) {
  std::mt19937 random(20261203);
  std::uniform_real_distribution<double> unit(-1, 1), slab(0.01, 0.02), weight(0.1, 1);
  const std::array<double, 4> margins{1e-14, 1e-14, 1e-14, 1e-14};
  int found = 0;
  for (int trial = 0; trial < 200; ++trial) {
    Eigen::Vector4d hidden(unit(random), unit(random), unit(random), unit(random));
    hidden.normalize();
    // The vectors: a lopsided cloud (most near one direction of the slab, a few far off) so that
    // their mean is a poor separator.
    const Eigen::Vector4d a = Eigen::Vector4d(unit(random), unit(random), unit(random), unit(random)),
                          b = Eigen::Vector4d(unit(random), unit(random), unit(random), unit(random));
    BernsteinTensor<4> minors({3, 3, 1, 1}, 4);
    const std::size_t n = minors.count();
    std::vector<Eigen::Vector4d> vectors;
    for (std::size_t i = 0; i < n; ++i) {
      const Eigen::Vector4d centre = i < n - 3 ? Eigen::Vector4d(3 * a) : Eigen::Vector4d(-2 * a + static_cast<double>(i - (n - 3)) * b);
      Eigen::Vector4d v = centre + 0.3 * Eigen::Vector4d(unit(random), unit(random), unit(random), unit(random));
      v -= hidden.dot(v) * hidden;
      if (v.norm() < 1e-3) v = Eigen::Vector4d(1, 0, 0, 0) - hidden(0) * hidden;
      v += slab(random) * v.norm() * hidden;
      vectors.push_back(v);
    }
    for (std::size_t i = 0; i < n; ++i)
      for (Eigen::Index k = 0; k < 4; ++k) minors.coefficients[4 * i + static_cast<std::size_t>(k)] = vectors[i](k);
    const RankCertificate separated = bernstein_rank_certificate(minors, margins);
    // Sign and NoFold are proofs too (one component happens to keep a sign); count Hull alone.
    EXPECT_NE(separated, RankCertificate::None) << "trial " << trial;
    found += separated == RankCertificate::Hull;
    // Replace the last vector by minus a positive combination of the others: the origin is then
    // a convex combination of all of them.
    Eigen::Vector4d combination = Eigen::Vector4d::Zero();
    for (std::size_t i = 0; i + 1 < n; ++i) combination += weight(random) * vectors[i];
    for (Eigen::Index k = 0; k < 4; ++k) minors.coefficients[4 * (n - 1) + static_cast<std::size_t>(k)] = -combination(k);
    EXPECT_EQ(bernstein_rank_certificate(minors, margins), RankCertificate::None) << "trial " << trial;
  }
  EXPECT_GT(found, 150);
}

TEST(SubJacobians, ConeCertificateProvesAnUnfoldedGenerator) {
  const auto map = test_support::translated_generator({{1.0, 0, 0, 1}, {0.2, 1, 1, 0}}, {1, 1, 1}, {0.3, 0.2, 1.0});
  BernsteinTensor<4> geometry;
  geometry.degrees = map.degrees();
  geometry.components = 3;
  geometry.coefficients = map.homogeneous();
  EXPECT_EQ(cone_rank_certificate(geometry, {1, 1, 1, 1}), RankCertificate::Cone);
}

TEST(SubJacobians, RejectsMapsNotIntoThreeSpace) {
  std::mt19937 rng(5);
  const auto map = test_support::random_spline<4>(rng, {1, 1, 1, 1}, 1, 2, false);
  EXPECT_THROW(sub_jacobian_coefficients(map), InvalidInput);
  const auto spline = test_support::random_spline<4>(rng, {1, 1, 1, 1}, 2, 3, false);
  EXPECT_THROW(sub_jacobian_coefficients(spline), InvalidInput);
}

}  // namespace
}  // namespace volspline
