#include "volspline/construct/example_solids.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "volspline/extract/face_tessellation.h"
#include "volspline/mesh/mesh_checks.h"

namespace volspline {
namespace {

TEST(HalfCylinderShell, LiesExactlyOnTheCylinders) {
  const auto v = half_cylinder_shell(1.0, 2.0, 3.0);
  std::mt19937 rng(80);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 500; ++i) {
    const double a = u(rng), b = u(rng), c = u(rng);
    const auto x = v.evaluate({a, b, c});
    EXPECT_NEAR(std::hypot(x[0], x[1]), 1.0 + a, 1e-12);  // radius is linear in u
    EXPECT_NEAR(x[2], 3.0 * c, 1e-12);
    EXPECT_GE(x[1], -1e-15);  // the upper half
    // the inner and outer faces lie on the analytic cylinders
    const auto inner = v.evaluate({0.0, b, c});
    const auto outer = v.evaluate({1.0, b, c});
    EXPECT_NEAR(std::hypot(inner[0], inner[1]), 1.0, 1e-12);
    EXPECT_NEAR(std::hypot(outer[0], outer[1]), 2.0, 1e-12);
  }
  // Its boundary encloses half an annulus times the height: pi/2 (4 - 1) 3.
  // Polygonal approximations converge quadratically in the resolution.
  const double exact = std::numbers::pi / 2 * 3 * 3;
  const auto coarse = tessellate_faces(v, {.resolution = 32});
  const auto fine = tessellate_faces(v, {.resolution = 64});
  EXPECT_TRUE(edge_statistics(fine).closed());
  const double e_coarse = exact - enclosed_volume(coarse), e_fine = exact - enclosed_volume(fine);
  EXPECT_GT(e_fine, 0.0);  // inscribed polygons
  EXPECT_LT(e_fine, 1e-2);
  EXPECT_NEAR(e_coarse / e_fine, 4.0, 0.2);
}

TEST(ExampleSolids, AreClosedWithPositiveVolume) {
  for (const auto& v : {bent_tricubic_volume(), twisted_volume(0.25)}) {
    const auto mesh = tessellate_faces(v, {.resolution = 12});
    EXPECT_TRUE(edge_statistics(mesh).closed());
    EXPECT_GT(enclosed_volume(mesh), 0.5);
  }
  // Untwisted, the column is the unit square times [0, 3].
  EXPECT_NEAR(enclosed_volume(tessellate_faces(twisted_volume(0.0), {.resolution = 4})), 3.0, 1e-12);
}

}  // namespace
}  // namespace volspline
