#include "volspline/analysis/scalar_fields.h"

#include <random>

#include <gtest/gtest.h>

#include "support/jacobian_test_volumes.h"
#include "support/test_splines.h"
#include "volspline/core/error.h"

namespace volspline {
namespace {

std::vector<Eigen::Vector3d> random_parameters(std::mt19937& rng, const BSplineVolume& v, int count) {
  std::vector<Eigen::Vector3d> t(static_cast<std::size_t>(count));
  for (auto& p : t)
    for (int d = 0; d < 3; ++d) p[d] = std::uniform_real_distribution<double>(v.domain_min(d), v.domain_max(d))(rng);
  return t;
}

TEST(ScalarField, NamesRoundTrip) {
  for (const std::string name : {"jacobian", "u", "v", "w", "density"}) EXPECT_EQ(scalar_field_named(name).name(), name);
  EXPECT_EQ(scalar_field_named("density").kind, ScalarKind::Attribute);
  EXPECT_THROW(scalar_field_named(""), InvalidInput);
}

TEST(ScalarField, JacobianIsTheAnalyticDeterminant) {
  // The fold volume's J = v^2 - s(u, w) in closed form.
  const BSplineVolume v = test_support::fold_volume();
  std::mt19937 rng(2);
  const auto t = random_parameters(rng, v, 50);
  const auto j = evaluate_scalar_field(v, scalar_field_named("jacobian"), t);
  for (std::size_t i = 0; i < t.size(); ++i) EXPECT_NEAR(j[i], t[i][1] * t[i][1] - test_support::fold_s(t[i][0], t[i][2]), 1e-12);
}

TEST(ScalarField, ParametersAreTheParameters) {
  std::mt19937 rng(4);
  const BSplineVolume v = test_support::random_spline<3>(rng, {2, 2, 2}, 2, 3, false);
  const auto t = random_parameters(rng, v, 20);
  for (int d = 0; d < 3; ++d) {
    const auto values = evaluate_scalar_field(v, scalar_field_named(std::string(1, "uvw"[d])), t);
    for (std::size_t i = 0; i < t.size(); ++i) EXPECT_EQ(values[i], t[i][d]);
  }
  EXPECT_THROW(evaluate_scalar_field(v, scalar_field_named("u"), {Eigen::Vector3d::Constant(1e9)}), InvalidInput);
}

TEST(ScalarField, AnAttributeEqualToACoordinateReproducesThatCoordinate) {
  // With the x coordinates of the control points as the attribute, a(t) = x(t) exactly, also for
  // rational volumes (the attribute shares the weights).
  std::mt19937 rng(6);
  for (const bool rational : {false, true}) {
    const BSplineVolume v = test_support::random_spline<3>(rng, {2, 3, 1}, 2, 3, rational);
    std::vector<double> x;
    for (std::size_t i = 0; i < v.points().size(); i += 3) x.push_back(v.points()[i]);
    const auto t = random_parameters(rng, v, 30);
    const auto a = evaluate_scalar_field(v, scalar_field_named("x_copy"), t, x);
    for (std::size_t i = 0; i < t.size(); ++i) EXPECT_NEAR(a[i], v.evaluate({t[i][0], t[i][1], t[i][2]})[0], 1e-12);
    x.pop_back();
    EXPECT_THROW(evaluate_scalar_field(v, scalar_field_named("x_copy"), t, x), InvalidInput);
  }
}

}  // namespace
}  // namespace volspline
