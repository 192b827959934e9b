// The exact primitives integrate to their analytic volumes and centroids (issue 3: 1e-10
// relative): two independent pieces of the library, constructions and quadrature, agree with
// closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "volspline/analysis/mass_properties.h"
#include "volspline/construct/primitives.h"

namespace volspline {
namespace {

constexpr double pi = std::numbers::pi;

void expect_volume(const BSplineVolume& v, double expected, const Eigen::Vector3d& centroid) {
  const MassProperties m = mass_properties(v);
  EXPECT_TRUE(m.converged);
  EXPECT_NEAR(m.volume, expected, 1e-10 * expected);
  EXPECT_LT((m.centroid - centroid).norm(), 1e-10 * std::cbrt(expected));
}

TEST(PrimitiveMass, VolumesAndCentroidsAreAnalytic) {
  const Eigen::Vector3d c(0.5, -1.0, 2.0);
  expect_volume(ball(1.7, c), 4.0 / 3.0 * pi * std::pow(1.7, 3), c);
  expect_volume(torus(3.0, 0.8, 360.0, c), 2.0 * pi * pi * 3.0 * 0.8 * 0.8, c);
  expect_volume(box(Eigen::Vector3d(1.0, 2.0, 3.0), c), 6.0, c);
  // Solid and hollow cylinders and the frustum: volume pi h (r1^2 + r1 r2 + r2^2) / 3, the
  // centroid on the axis at h (r1^2 + 2 r1 r2 + 3 r2^2) / (4 (r1^2 + r1 r2 + r2^2)) above the base.
  const MassProperties cyl = mass_properties(cylinder(1.5, 2.0, 0.0));
  EXPECT_NEAR(cyl.volume, pi * 1.5 * 1.5 * 2.0, 1e-10 * cyl.volume);
  const MassProperties ring = mass_properties(cylinder(1.5, 2.0, 0.5));
  EXPECT_NEAR(ring.volume, pi * (1.5 * 1.5 - 0.25) * 2.0, 1e-10 * ring.volume);
  const double r1 = 2.0, r2 = 0.7, h = 3.0;
  const MassProperties frustum = mass_properties(cone(r1, r2, h));
  EXPECT_NEAR(frustum.volume, pi * h * (r1 * r1 + r1 * r2 + r2 * r2) / 3.0, 1e-10 * frustum.volume);
  const MassProperties solid_cone = mass_properties(cone(r1, 0.0, h));
  EXPECT_NEAR(solid_cone.volume, pi * h * r1 * r1 / 3.0, 1e-10 * solid_cone.volume);
  // the axial centroid offset is the same whatever the base height convention: compare the
  // distance between the cone's and the frustum's centroids along the axis
  const double zc_cone = h / 4.0, zc_frustum = h * (r1 * r1 + 2 * r1 * r2 + 3 * r2 * r2) / (4 * (r1 * r1 + r1 * r2 + r2 * r2));
  EXPECT_NEAR((frustum.centroid - solid_cone.centroid).norm(), std::abs(zc_frustum - zc_cone), 1e-10);
  // Lasser Fig. 2: a half torus, weight-0 control points included
  const MassProperties half = mass_properties(half_torus(2.0, 1.0));
  EXPECT_NEAR(half.volume, pi * pi * 2.0 * 1.0, 1e-10 * half.volume);
}

}  // namespace
}  // namespace volspline
