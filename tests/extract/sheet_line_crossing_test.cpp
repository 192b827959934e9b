// Newton onto the sheets of a swept solid's superset: the crossings of short segments through
// the superset's triangles with the sheets they approximate lie on the analytic surfaces (a
// ball along a segment: the fold is the capsule's cylinder, the cap squares its end spheres).
#include "volspline/extract/sheet_line_crossing.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "volspline/construct/swept_examples.h"
#include "volspline/extract/swept_envelope.h"

namespace volspline {
namespace {

TEST(SheetLineCrossing, CrossingsOfTheCapsulesSheetsLieOnTheCapsule) {
  const double r = 0.5;
  const Eigen::Vector3d d(1.2, 0.3, -0.2);
  const auto patches = swept_patches(translated_ball(r, d));
  const SweptEnvelope superset = swept_envelope_superset(patches);
  ASSERT_EQ(superset.sheets.size(), superset.mesh.num_triangles());
  int folds = 0, folds_found = 0, caps = 0, caps_found = 0;
  for (std::size_t f = 0; f < superset.mesh.num_triangles(); f += 7) {
    const SupersetSheet& sheet = superset.sheets[f];
    const auto& tri = superset.mesh.triangles[f];
    const auto v0 = static_cast<std::size_t>(tri[0]);
    const bool fold = sheet.fold;
    // A cap square: the sphere (u = 1) at t = 0 or t = 1.
    const bool cap = !fold && sheet.fixed == ((1 << 0) | (1 << 3)) && superset.mesh.parameters[v0][0] == 1;
    if (!fold && !cap) continue;
    std::array<double, 4> start{};
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (int j = 0; j < 3; ++j) {
      const auto v = static_cast<std::size_t>(tri[static_cast<std::size_t>(j)]);
      for (int k = 0; k < 3; ++k) start[static_cast<std::size_t>(k)] += superset.mesh.parameters[v][k] / 3;
      start[3] += superset.times[v] / 3;
      centre += superset.mesh.positions[v] / 3;
    }
    for (int k = 0; k < 4; ++k)
      if ((sheet.fixed >> k) & 1) start[static_cast<std::size_t>(k)] = k < 3 ? superset.mesh.parameters[v0][k] : superset.times[v0];
    const Eigen::Vector3d& p0 = superset.mesh.positions[v0];
    const Eigen::Vector3d normal =
        (superset.mesh.positions[static_cast<std::size_t>(tri[1])] - p0).cross(superset.mesh.positions[static_cast<std::size_t>(tri[2])] - p0);
    if (!(normal.norm() > 0)) continue;
    const Eigen::Vector3d a = centre - 0.05 * normal.normalized(), b = centre + 0.05 * normal.normalized();
    const auto c = sheet_line_crossing<4>(patches[0], sheet, start, 0.5, a, b);
    (fold ? folds : caps) += 1;
    if (!c) continue;
    (fold ? folds_found : caps_found) += 1;
    Eigen::Vector3d x;
    patches[0].evaluate(c->parameter, x.data());
    // On the segment, at its lambda.
    EXPECT_LT((x - (a + c->lambda * (b - a))).norm(), 1e-9);
    EXPECT_GE(c->lambda, 0);
    EXPECT_LE(c->lambda, 1);
    if (fold) {
      // The fold of the moving sphere is the cylinder of radius r about the segment.
      const double t = x.dot(d) / d.squaredNorm();
      EXPECT_NEAR((x - t * d).norm(), r, 1e-9);
      EXPECT_NEAR(c->normal.dot(d), 0, 1e-6);
    } else {
      EXPECT_NEAR((x - c->parameter[3] * d).norm(), r, 1e-9);
    }
    EXPECT_NEAR(c->normal.norm(), c->normal.isZero() ? 0 : 1, 1e-12);
  }
  ASSERT_GT(folds, 20);
  ASSERT_GT(caps, 20);
  // Newton from the triangle's centre reaches its sheet for most triangles: measured 70 % of
  // the folds' (1,327 of 1,900; not yet understood which fail and why: the contouring then tries
  // the other sheets near the edge) and of the caps' at least 90 %.
  EXPECT_GE(folds_found, 0.65 * folds);
  EXPECT_GE(caps_found, 0.9 * caps);
}

TEST(SheetLineCrossing, RefusesSheetsItDoesNotKnow) {
  const auto patches = swept_patches(translated_ball(0.5, Eigen::Vector3d(1, 0, 0)));
  const std::array<double, 4> start{1, 0.5, 0.5, 0.5};
  const Eigen::Vector3d a(0, 0, 0), b(1, 1, 1);
  // Three free parameters without the fold condition, one free parameter, no free parameter.
  EXPECT_FALSE(sheet_line_crossing<4>(patches[0], SupersetSheet{1, false}, start, 0.5, a, b));
  EXPECT_FALSE(sheet_line_crossing<4>(patches[0], SupersetSheet{7, false}, start, 0.5, a, b));
  EXPECT_FALSE(sheet_line_crossing<4>(patches[0], SupersetSheet{15, false}, start, 0.5, a, b));
  // A segment of zero length.
  EXPECT_FALSE(sheet_line_crossing<4>(patches[0], SupersetSheet{9, false}, start, 0.5, a, a));
}

}  // namespace
}  // namespace volspline
