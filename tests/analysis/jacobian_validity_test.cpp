#include "volspline/analysis/jacobian_validity.h"

#include <gtest/gtest.h>

#include "support/jacobian_test_volumes.h"
#include "volspline/construct/example_solids.h"
#include "volspline/construct/paper_examples.h"
#include "volspline/construct/primitives.h"
#include "volspline/spline/affine_map.h"

namespace volspline {
namespace {

using test_support::jacobian_at;

TEST(JacobianValidity, RightAndLeftHandedVolumesAreValidWithTheirOrientation) {
  Eigen::Matrix3d mirror = Eigen::Matrix3d::Identity();
  mirror(0, 0) = -1;
  for (const BSplineVolume& v : {bent_tricubic_volume(), cylinder(2.0, 1.0, 0.5), box(Eigen::Vector3d(1, 2, 3))}) {
    const auto right = check_jacobian(v);
    EXPECT_EQ(right.verdict, JacobianVerdict::Valid);
    const auto left = check_jacobian(transform_affine(v, mirror, Eigen::Vector3d::Zero()));
    EXPECT_EQ(left.verdict, JacobianVerdict::Valid);
    EXPECT_EQ(right.orientation, -left.orientation);
    // The bounds are certified: they contain J everywhere we look.
    for (double a : {0.0, 0.37, 1.0})
      for (double b : {0.0, 0.61, 1.0})
        for (double c : {0.0, 0.5, 1.0}) {
          const std::array<double, 3> t{v.domain_min(0) + a * (v.domain_max(0) - v.domain_min(0)),
                                        v.domain_min(1) + b * (v.domain_max(1) - v.domain_min(1)),
                                        v.domain_min(2) + c * (v.domain_max(2) - v.domain_min(2))};
          const double j = jacobian_at(v, t);
          EXPECT_GE(j, right.lower - 1e-12 * (1 + std::abs(right.lower)));
          EXPECT_LE(j, right.upper + 1e-12 * (1 + std::abs(right.upper)));
        }
  }
}

TEST(JacobianValidity, NearlySingularButPositiveIsValid) {
  // min J = 1e-6 x max J (max about 0.49 + e at a corner).
  const double e = 0.49e-6;
  const auto v = test_support::near_singular_volume(e);
  const auto r = check_jacobian(v);
  EXPECT_EQ(r.verdict, JacobianVerdict::Valid);
  EXPECT_EQ(r.orientation, 1);
  EXPECT_GT(r.lower, 0);
  EXPECT_LE(r.lower, e * 1.000001);
}

TEST(JacobianValidity, TouchingBelowZeroIsInvalidWithAWitness) {
  const double e = -0.49e-6;  // J = (v - c(u))^2 - 4.9e-7 < 0 in a thin slab around v = c(u)
  const auto v = test_support::near_singular_volume(e);
  const auto r = check_jacobian(v);
  ASSERT_EQ(r.verdict, JacobianVerdict::Invalid);
  ASSERT_TRUE(r.witness.has_value());
  EXPECT_EQ(r.orientation, 0);
  EXPECT_LT(jacobian_at(v, *r.witness), 0);
  EXPECT_LT(r.witness_value, 0);
  ASSERT_TRUE(r.reference_point.has_value());
  EXPECT_GT(jacobian_at(v, *r.reference_point), 0);
}

TEST(JacobianValidity, FoldedPaperExamplesAreInvalid) {
  for (const BSplineVolume& v : {swept_patch(), twisted_loft(), curved_loft(), half_cylinder_sweep()}) {
    const auto r = check_jacobian(v);
    ASSERT_EQ(r.verdict, JacobianVerdict::Invalid);
    EXPECT_LT(r.lower, 0);
    EXPECT_GT(r.upper, 0);
    const double j = jacobian_at(v, *r.witness);
    if (r.witness_value != 0) {
      EXPECT_EQ(j > 0, r.witness_value > 0);
    }
  }
}

TEST(JacobianValidity, CollapsedControlPointsGiveAnExactZeroWitness) {
  const auto r = check_jacobian(ball(1.0));
  ASSERT_EQ(r.verdict, JacobianVerdict::Invalid);
  EXPECT_EQ(r.witness_value, 0);
  EXPECT_NEAR(jacobian_at(ball(1.0), *r.witness), 0, 1e-14);
}

TEST(JacobianValidity, ConeBoundsReachTheSameVerdictsWithMoreCells) {
  JacobianValidityOptions cone;
  cone.bounds = JacobianBoundMethod::Cone;
  const auto b = check_jacobian(bent_tricubic_volume());
  const auto c = check_jacobian(bent_tricubic_volume(), cone);
  EXPECT_EQ(c.verdict, JacobianVerdict::Valid);
  EXPECT_GE(c.cells, b.cells);
  EXPECT_EQ(check_jacobian(twisted_loft(), cone).verdict, JacobianVerdict::Invalid);
}

TEST(JacobianValidity, BudgetExhaustedIsUndecided) {
  JacobianValidityOptions o;
  o.max_cells = 1;
  const auto r = check_jacobian(test_support::near_singular_volume(0.49e-6), o);
  EXPECT_EQ(r.verdict, JacobianVerdict::Undecided);
  EXPECT_EQ(r.orientation, 0);
  EXPECT_LE(r.lower, 0.49e-6);
}

}  // namespace
}  // namespace volspline
