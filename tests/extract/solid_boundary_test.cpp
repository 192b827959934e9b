#include "volspline/extract/solid_boundary.h"

#include <gtest/gtest.h>

#include <map>
#include <random>

#include "support/jacobian_test_volumes.h"
#include "support/test_splines.h"
#include "volspline/construct/example_solids.h"
#include "volspline/construct/paper_examples.h"
#include "volspline/construct/primitives.h"
#include "volspline/core/error.h"
#include "volspline/mesh/mesh_checks.h"

namespace volspline {
namespace {

using test_support::on_domain_boundary;

using test_support::fold_s;
using test_support::jacobian_at;


// Joy–Duchaineau §7: no cracks. Every edge of the implicit surface is shared by exactly two of
// its triangles, unless both its ends lie on the boundary of the domain.
void expect_crack_free(const BSplineVolume& v, const TriangleMesh& mesh) {
  std::map<std::pair<int, int>, int> edges;
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    if (mesh.parts[f] != part_number(Part::JacobianZero)) continue;
    const auto& t = mesh.triangles[f];
    for (int e = 0; e < 3; ++e) {
      const int a = t[static_cast<std::size_t>(e)], b = t[static_cast<std::size_t>((e + 1) % 3)];
      ++edges[{std::min(a, b), std::max(a, b)}];
    }
  }
  int inner = 0;
  for (const auto& [edge, count] : edges) {
    const bool boundary = on_domain_boundary(v, mesh.parameters[static_cast<std::size_t>(edge.first)]) &&
                          on_domain_boundary(v, mesh.parameters[static_cast<std::size_t>(edge.second)]);
    if (boundary) {
      EXPECT_LE(count, 2);
    } else {
      ++inner;
      EXPECT_EQ(count, 2) << "edge " << edge.first << "-" << edge.second << " at "
                          << mesh.parameters[static_cast<std::size_t>(edge.first)].transpose();
    }
  }
  EXPECT_GT(inner, 0);
}

TEST(SolidBoundary, KnownFoldIsFoundWithinTheToleranceAndCoveredBothWays) {
  const auto v = test_support::fold_volume();  // J = v^2 - s(u, w) on [0,1] x [-1,1] x [0,1]
  BoundaryOptions options;
  options.tolerance = 1e-3;
  const auto result = jacobian_zero_surface(v, options);
  const TriangleMesh& mesh = result.mesh;
  ASSERT_GT(mesh.num_triangles(), 50u);
  expect_crack_free(v, mesh);
  // Every vertex satisfies J = v^2 - s = 0 within the tolerance (relative to the largest |J|,
  // 1 at v = +-1, u = w = 0), and lies within a small domain distance of the analytic sheets.
  const double max_j = 1.0 - 0.25;
  double worst = 0;
  for (const auto& p : mesh.parameters) {
    const double j = p[1] * p[1] - fold_s(p[0], p[2]);
    EXPECT_LE(std::abs(j), options.tolerance * 2 * max_j);
    worst = std::max(worst, std::abs(std::abs(p[1]) - std::sqrt(fold_s(p[0], p[2]))));
  }
  EXPECT_LT(worst, 2e-3);
  EXPECT_LE(result.stats.max_rel_jacobian_at_vertices, 2 * options.tolerance);
  // Coverage: every point of both analytic sheets is near the extracted surface (in the domain).
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(0, 1);
  const double cover = 0.05;
  for (int n = 0; n < 200; ++n) {
    const double u = unit(rng), w = unit(rng), sign = n % 2 ? 1.0 : -1.0;
    const Eigen::Vector3d q(u, sign * std::sqrt(fold_s(u, w)), w);
    double best = 1e9;
    for (const auto& p : mesh.parameters) best = std::min(best, (p - q).norm());
    EXPECT_LT(best, cover) << q.transpose();
  }
}

TEST(SolidBoundary, SnappedVerticesLieOnTheZeroSet) {
  const auto v = test_support::fold_volume();
  BoundaryOptions options;
  options.snap = true;
  const auto result = jacobian_zero_surface(v, options);
  for (const auto& p : result.mesh.parameters) EXPECT_LT(std::abs(p[1] * p[1] - fold_s(p[0], p[2])), 1e-12);
  expect_crack_free(v, result.mesh);
}

TEST(SolidBoundary, SweptPatchZeroSetIsThePlaneVTwoThirds) {
  const auto v = swept_patch();
  BoundaryOptions options;
  options.snap = true;
  const auto result = solid_boundary(v, options);
  ASSERT_GT(result.stats.triangles[6], 0);
  for (std::size_t f = 0; f < result.mesh.num_triangles(); ++f) {
    if (result.mesh.parts[f] != part_number(Part::JacobianZero)) continue;
    for (int k : result.mesh.triangles[f]) EXPECT_NEAR(result.mesh.parameters[static_cast<std::size_t>(k)][1], 2.0 / 3.0, 1e-12);
  }
  for (int part = 0; part < 6; ++part) EXPECT_GT(result.stats.triangles[static_cast<std::size_t>(part)], 0);
  expect_crack_free(v, result.mesh);
}

TEST(SolidBoundary, CellsOfVeryDifferentSizesStayCrackFree) {
  // twisted-loft refines strongly near the fold and hardly elsewhere.
  const auto v = twisted_loft();
  BoundaryOptions options;
  options.tolerance = 1e-4;
  const auto result = jacobian_zero_surface(v, options);
  EXPECT_GT(result.stats.cells_kept, 100);
  expect_crack_free(v, result.mesh);
  const auto curved = jacobian_zero_surface(curved_loft(), options);
  expect_crack_free(curved_loft(), curved.mesh);
}

TEST(SolidBoundary, ValidVolumesHaveNoImplicitSurface) {
  for (const BSplineVolume& v : {bent_tricubic_volume(), cylinder(2.0, 1.0, 0.5)}) {
    const auto result = solid_boundary(v);
    EXPECT_EQ(result.stats.triangles[6], 0);
    EXPECT_EQ(result.stats.cells_kept, 0);
  }
  EXPECT_TRUE(edge_statistics(solid_boundary(bent_tricubic_volume()).mesh).closed());
}

TEST(SolidBoundary, UniformBaselineFindsTheSameSurface) {
  const auto v = test_support::fold_volume();
  BoundaryOptions options;
  options.method = ZeroSurfaceMethod::Uniform;
  options.resolution = 40;
  const auto result = jacobian_zero_surface(v, options);
  expect_crack_free(v, result.mesh);
  for (const auto& p : result.mesh.parameters) EXPECT_LT(std::abs(std::abs(p[1]) - std::sqrt(fold_s(p[0], p[2]))), 5e-3);
}

TEST(SolidBoundary, ConeBoundsGiveTheSameSurfaceWithMoreCells) {
  const auto v = twisted_loft();
  BoundaryOptions bezier, cone;
  cone.bounds = JacobianBoundMethod::Cone;
  bezier.stop = StopCriterion::Width;
  bezier.tolerance = cone.tolerance = 0.1;
  bezier.max_cells = cone.max_cells = 30000;
  const auto b = jacobian_zero_surface(v, bezier);
  const auto c = jacobian_zero_surface(v, cone);
  EXPECT_GT(c.stats.cells_examined, b.stats.cells_examined);
  expect_crack_free(v, c.mesh);
}

TEST(SolidBoundary, BadOptionsAreRejected) {
  BoundaryOptions o;
  o.tolerance = 0;
  EXPECT_THROW(jacobian_zero_surface(swept_patch(), o), InvalidInput);
  o = {};
  o.bounds = JacobianBoundMethod::Cone;
  EXPECT_THROW(jacobian_zero_surface(torus(3.0, 1.0), o), InvalidInput);
}

}  // namespace
}  // namespace volspline
