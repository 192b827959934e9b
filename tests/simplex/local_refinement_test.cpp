// Local refinement (simplex/local_refinement.h): the split domain is valid and has the same
// volume, polynomials of degree <= n are reproduced after the re-fit, and bad requests refused.
#include <random>

#include <gtest/gtest.h>

#include "support/simplex_domains.h"
#include "volspline/core/error.h"
#include "volspline/mesh/tetrahedral_mesh.h"
#include "volspline/simplex/dms_spline_evaluator.h"
#include "volspline/simplex/local_refinement.h"

namespace volspline {
namespace {

TEST(LocalRefinement, SplitKeepsTheDomainAndReproducesPolynomials) {
  DmsSplineVolume v = test_support::cube_simplex_volume(2);
  // A quadratic attribute: reproduced before and after.
  set_column_from_blossom(v, 3, [](std::span<const Eigen::Vector3d> a) { return a[0].dot(a[1]) + a[0].x() + a[1].x() + 0.5; });
  const int t = 5;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (int c = 0; c < 4; ++c) centroid += v.domain().points[static_cast<std::size_t>(v.domain().tetrahedra[t][static_cast<std::size_t>(c)])] / 4;
  LocalRefinementReport report;
  const DmsSplineVolume r = refine_tetrahedron(v, t, centroid, &report);
  EXPECT_EQ(r.domain().tetrahedra.size(), v.domain().tetrahedra.size() + 3);
  EXPECT_EQ(report.new_vertex, static_cast<int>(v.domain().points.size()));
  EXPECT_NEAR(tetrahedral_mesh_volume(r.domain()), 1.0, 1e-14);
  EXPECT_LT(report.max_error, 1e-7);
  DmsSplineEvaluator evaluator(r);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.05, 0.95);
  for (int i = 0; i < 50; ++i) {
    const Eigen::Vector3d x(u(rng), u(rng), u(rng));
    const DmsSplinePoint p = evaluator.evaluate(x);
    EXPECT_NEAR((p.value.head<3>() - x).norm(), 0.0, 1e-7);
    EXPECT_NEAR(p.value[3], x.dot(x) + 2 * x.x() + 0.5, 1e-7);
  }
}

TEST(LocalRefinement, RefusesPointsNotStrictlyInside) {
  const DmsSplineVolume v = test_support::cube_simplex_volume(1);
  const Eigen::Vector3d corner = v.domain().points[static_cast<std::size_t>(v.domain().tetrahedra[0][0])];
  EXPECT_THROW(refine_tetrahedron(v, 0, corner, nullptr), InvalidInput);
  EXPECT_THROW(refine_tetrahedron(v, -1, corner, nullptr), InvalidInput);
  EXPECT_THROW(refine_tetrahedron(v, 0, Eigen::Vector3d(9, 9, 9), nullptr), InvalidInput);
}

}  // namespace
}  // namespace volspline
