#include "analysis/newton_in_domain.h"

#include <gtest/gtest.h>

#include <random>

#include "support/swept_solids.h"
#include "volspline/construct/primitives.h"
#include "volspline/core/error.h"

namespace volspline {
namespace {

// The ball of radius 0.6 at the origin translated along `offset`: a capsule.
BSplineHypervolume capsule_map(const Eigen::Vector3d& offset) { return test_support::translated_along(ball(0.6), offset); }

TEST(NewtonInDomain, MinimumNormStepsSolveTheUnderdeterminedSweep) {
  const Eigen::Vector3d offset(1.2, -0.7, 0.9);
  const BSplineHypervolume s = capsule_map(offset);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int i = 0; i < 20; ++i) {
    // A point of the capsule and a start a little away from one of its preimages.
    const std::array<double, 4> p{unit(rng), unit(rng), unit(rng), unit(rng)};
    const Eigen::Vector3d x = s.evaluate(p);
    const std::array<double, 4> start{std::clamp(p[0] + 0.05, 0.0, 1.0), std::clamp(p[1] - 0.04, 0.0, 1.0), p[2], std::clamp(p[3] + 0.1, 0.0, 1.0)};
    const auto r = detail::newton_in_domain<4>(s, x, start, 1e-12);
    ASSERT_TRUE(r.converged);
    EXPECT_TRUE(s.contains(r.parameter));
    EXPECT_LE((Eigen::Vector3d(s.evaluate(r.parameter)) - x).norm(), 1e-12);
  }
}

TEST(NewtonInDomain, OutsideAFoldItEndsAtTheClosestPointWithItsNormal) {
  // Outside the capsule's cylinder the closest point is on the envelope, where s(1, v, w, t) has
  // a rank-2 Jacobian (the sweep direction is tangent to the sphere): the Hessian steps must
  // find it, and the residual direction must be the analytic normal, perpendicular to the axis.
  const Eigen::Vector3d offset(1.2, -0.7, 0.9);
  const BSplineHypervolume s = capsule_map(offset);
  const Eigen::Vector3d axis = offset.normalized();
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> unit(0, 1);
  for (const double distance : {1e-3, 1e-6}) {
    for (int i = 0; i < 10; ++i) {
      // Drawn one by one: the order in which a constructor's arguments are evaluated is
      // unspecified (g++ and clang differ). This order is g++'s, which chose the cases below.
      const double nz = unit(rng) - 0.5, ny = unit(rng) - 0.5, nx = unit(rng) - 0.5;
      Eigen::Vector3d n(nx, ny, nz);
      n = (n - n.dot(axis) * axis).normalized();
      const double t = 0.2 + 0.6 * unit(rng);
      const Eigen::Vector3d x = t * offset + (0.6 + distance) * n;
      // Start from a nearby point of the sphere through the ball at a different t.
      std::array<double, 4> start{0.9, 0.5, 0.5, std::clamp(t + 0.1, 0.0, 1.0)};
      double nearest = 1e9;
      for (double v = 0; v <= 1; v += 0.125)
        for (double w = 0; w <= 1; w += 0.0625) {
          const std::array<double, 4> q{0.9, v, w, start[3]};
          const double d = (Eigen::Vector3d(s.evaluate(q)) - x).norm();
          if (d < nearest) {
            nearest = d;
            start = q;
          }
        }
      const auto r = detail::newton_in_domain<4>(s, x, start, 1e-12);
      EXPECT_FALSE(r.converged);
      EXPECT_NEAR(r.residual, distance, 1e-9 * distance + 1e-15);
      EXPECT_EQ(r.parameter[0], 1.0);  // held at the bound u = 1, the sphere
      const Eigen::Vector3d normal = (x - r.value) / r.residual;
      EXPECT_LT((normal - n).norm(), 1e-5) << "distance " << distance;
    }
  }
}

TEST(NewtonInDomain, DegenerateFacesAndCornersOfTheDomain) {
  // The ball's centre is the whole face u = 0 (J = 0 there); the cube's closest point to a
  // point beyond a corner is the corner, with every coordinate held at a bound.
  const BSplineVolume b = ball(1.0);
  const auto centre = detail::newton_in_domain<3>(b, Eigen::Vector3d::Zero(), {0.3, 0.4, 0.2}, 1e-12);
  EXPECT_TRUE(centre.converged);
  const BSplineVolume cube = box(Eigen::Vector3d(1, 1, 1), Eigen::Vector3d(0.5, 0.5, 0.5));
  const auto corner = detail::newton_in_domain<3>(cube, Eigen::Vector3d(1.1, 1.2, -0.3), {0.5, 0.5, 0.5}, 1e-12);
  EXPECT_FALSE(corner.converged);
  EXPECT_EQ(corner.parameter, (std::array<double, 3>{1.0, 1.0, 0.0}));
  EXPECT_NEAR(corner.residual, std::sqrt(0.01 + 0.04 + 0.09), 1e-14);
  EXPECT_THROW(detail::newton_in_domain<3>(BSplineVolume({KnotVector(1, {0, 0, 1, 1}), KnotVector(1, {0, 0, 1, 1}), KnotVector(1, {0, 0, 1, 1})}, 2,
                                                         std::vector<double>(16, 0.0)),
                                           Eigen::Vector3d::Zero(), {0, 0, 0}, 1e-12),
               InvalidInput);
}

}  // namespace
}  // namespace volspline
