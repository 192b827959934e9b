// Isosurfaces of simplex spline attributes (Hua–He–Qin §6.2): vertices on the spline's level set
// (root finding), normals from the gradient, no cracks between domain tetrahedra.
#include <cmath>

#include <gtest/gtest.h>

#include "support/graded_domain.h"
#include "support/simplex_domains.h"
#include "volspline/core/error.h"
#include "volspline/extract/simplex_isosurface.h"
#include "volspline/extract/simplex_slices.h"
#include "volspline/mesh/longest_edge_bisection.h"
#include "volspline/mesh/mesh_checks.h"
#include "volspline/simplex/dms_spline_evaluator.h"
#include "volspline/simplex/knot_clouds.h"

namespace volspline {
namespace {

// |x − c|² as a spline of degree n >= 2: its blossom is Σ_a mean over ordered pairs of distinct
// arguments of (x_i − c)_a (x_j − c)_a.
double sphere_blossom(std::span<const Eigen::Vector3d> args, const Eigen::Vector3d& c) {
  double sum = 0;
  int pairs = 0;
  for (std::size_t i = 0; i < args.size(); ++i)
    for (std::size_t j = 0; j < args.size(); ++j)
      if (i != j) sum += (args[i] - c).dot(args[j] - c), ++pairs;
  return sum / pairs;
}

TEST(SimplexIsosurface, SphereOfAQuadraticAttributeIsExactClosedAndOriented) {
  DmsSplineVolume v = test_support::cube_simplex_volume(2, DmsControlSharing::Shared, 4);
  const Eigen::Vector3d c(0.5, 0.48, 0.52);
  set_column_from_blossom(v, 3, [&](std::span<const Eigen::Vector3d> a) { return sphere_blossom(a, c); });
  SimplexIsosurfaceOptions options;
  options.value = 0.3 * 0.3;
  options.subdivisions = 3;
  const SimplexIsosurface s = simplex_isosurface(v, options);
  ASSERT_GT(s.mesh.num_triangles(), 200u);
  for (std::size_t i = 0; i < s.mesh.num_vertices(); ++i) {
    EXPECT_NEAR((s.mesh.positions[i] - c).norm(), 0.3, 1e-10);
    // The normal points toward larger |x − c|²: outward.
    EXPECT_NEAR(s.normals[i].dot((s.mesh.positions[i] - c).normalized()), 1.0, 1e-9);
  }
  TriangleMesh welded = s.mesh;
  const EdgeStatistics edges = edge_statistics(welded);
  EXPECT_TRUE(edges.closed_and_oriented()) << "boundary edges " << edges.boundary_edges;
  // Oriented toward larger values: outward, so the enclosed volume is positive and close to the ball's.
  EXPECT_NEAR(enclosed_volume(s.mesh), 4.0 / 3.0 * M_PI * 0.027, 0.08 * 0.113);
  EXPECT_LT(s.largest_residual, 1e-11);
}

TEST(SimplexIsosurface, LinearAttributeGivesAPlaneAcrossTetrahedraOfEveryDegree) {
  for (const int degree : {1, 3}) {
    DmsSplineVolume v = test_support::cube_simplex_volume(degree);
    const Eigen::Vector3d a(1.0, 2.0, -1.0);
    set_column_from_blossom(v, 3, [&](std::span<const Eigen::Vector3d> args) {
      Eigen::Vector3d mean = Eigen::Vector3d::Zero();
      for (const auto& x : args) mean += x;
      return a.dot(mean) / static_cast<double>(args.size());
    });
    SimplexIsosurfaceOptions options;
    options.value = 0.9;
    options.subdivisions = 2;
    const SimplexIsosurface s = simplex_isosurface(v, options);
    ASSERT_GT(s.mesh.num_triangles(), 10u);
    for (std::size_t i = 0; i < s.mesh.num_vertices(); ++i) {
      EXPECT_NEAR(a.dot(s.mesh.positions[i]), 0.9, 1e-11);
      EXPECT_NEAR(s.normals[i].dot(a.normalized()), 1.0, 1e-12);
    }
    // An open surface whose only border is on ∂Ω: no cracks inside.
    const EdgeStatistics edges = edge_statistics(s.mesh);
    EXPECT_EQ(edges.nonmanifold_edges, 0u);
    EXPECT_EQ(edges.inconsistently_oriented_edges, 0u);
    for (const auto& t : s.mesh.triangles)
      for (int c = 0; c < 3; ++c) {
        const Eigen::Vector3d p = s.mesh.positions[static_cast<std::size_t>(t[static_cast<std::size_t>(c)])];
        EXPECT_TRUE((p.array() >= -1e-12).all() && (p.array() <= 1 + 1e-12).all());
      }
  }
}

// Fig. 13's local upsampling on a domain whose tetrahedra differ in size by a factor of about 30
// (a cluster of small ones in a corner, large ones around it): longest-edge bisection refines only
// the large ones, and the surface of a closed level set inside
// Ω is still closed (every edge shared by two triangles, consistently oriented), exact, and made
// from far fewer tetrahedra than uniform refinement to the same finest edge.
TEST(SimplexIsosurface, LocalBisectionOnGradedDomainIsClosedExactAndCheaperThanUniform) {
  TetrahedralMesh domain = test_support::clustered_cube_domain();
  const std::size_t domain_tetrahedra = domain.tetrahedra.size();
  const double longest = longest_edge_length(domain);
  KnotClouds clouds = generate_knot_clouds(domain, 2);
  DmsSplineVolume v(std::move(domain), std::move(clouds), DmsControlSharing::Shared, {"density"});
  const Eigen::Vector3d c(0.5, 0.48, 0.52);
  set_column_from_blossom(v, 3, [&](std::span<const Eigen::Vector3d> a) { return sphere_blossom(a, c); });
  SimplexIsosurfaceOptions options;
  options.value = 0.3 * 0.3;
  options.target_edge = 0.1;
  const SimplexIsosurface s = simplex_isosurface(v, options);
  ASSERT_GT(s.mesh.num_triangles(), 200u);
  EXPECT_EQ(s.subdivisions, 0);
  DmsSplineEvaluator evaluator(v);
  for (std::size_t i = 0; i < s.mesh.num_vertices(); ++i) {
    // On the spline's level set, to 1e-9 of the attribute's size (evaluated independently).
    const Eigen::Vector3d x = s.mesh.parameters[i];
    EXPECT_NEAR(evaluator.evaluate(x).value[3], 0.09, 1e-9 * 0.09);
    EXPECT_EQ(s.mesh.positions[i], evaluator.evaluate(x).value.head<3>());
    // And the spline reproduces |x − c|² (to the accuracy of the basis on these slivers).
    EXPECT_NEAR((s.mesh.positions[i] - c).squaredNorm(), 0.09, 1e-7);
    EXPECT_NEAR(s.normals[i].dot((s.mesh.positions[i] - c).normalized()), 1.0, 1e-6);
  }
  EXPECT_LT(s.largest_residual, 1e-9);
  const EdgeStatistics edges = edge_statistics(s.mesh);
  EXPECT_TRUE(edges.closed_and_oriented()) << "boundary edges " << edges.boundary_edges << ", inconsistent "
                                           << edges.inconsistently_oriented_edges << ", nonmanifold " << edges.nonmanifold_edges;
  EXPECT_NEAR(enclosed_volume(s.mesh), 4.0 / 3.0 * M_PI * 0.027, 0.05 * 0.113);
  // Uniform refinement to the same finest edge cuts every tetrahedron into k³, k = longest / target.
  const auto k = static_cast<long long>(std::ceil(longest / options.target_edge));
  EXPECT_LT(4 * s.sampled_tetrahedra, k * k * k * static_cast<long long>(domain_tetrahedra));
}

TEST(SimplexIsosurface, RefusesVolumesWithoutTheAttribute) {
  DmsSplineVolume v = test_support::cube_simplex_volume(1);
  SimplexIsosurfaceOptions options;
  options.attribute = "temperature";
  EXPECT_THROW(simplex_isosurface(v, options), InvalidInput);
  options = {};
  options.subdivisions = 65;
  EXPECT_THROW(simplex_isosurface(v, options), InvalidInput);
}

}  // namespace
}  // namespace volspline

namespace volspline {
namespace {

// Slices (extract/simplex_slices.h): a plane through the unit-cube domain is the unit square,
// every vertex on the plane, carrying the attribute's exact value.
TEST(SimplexSlices, PlaneThroughTheCubeIsTheUnitSquareCarryingTheAttribute) {
  DmsSplineVolume v = test_support::cube_simplex_volume(2);
  const Eigen::Vector3d a(0.4, -1.0, 2.0);
  set_column_from_blossom(v, 3, [&](std::span<const Eigen::Vector3d> args) { return a.dot((args[0] + args[1]) / 2) + 0.25; });
  const SimplexSlice slice = simplex_plane_slice(v, Plane{Eigen::Vector3d(0, 0, 2), 0.7}, {});
  ASSERT_GT(slice.mesh.num_triangles(), 20u);
  ASSERT_EQ(slice.values.size(), slice.mesh.num_vertices());
  for (std::size_t i = 0; i < slice.mesh.num_vertices(); ++i) {
    EXPECT_NEAR(slice.mesh.positions[i].z(), 0.35, 1e-12);
    EXPECT_NEAR(slice.values[i], a.dot(slice.mesh.positions[i]) + 0.25, 1e-10);
  }
  EXPECT_NEAR(surface_area(slice.mesh), 1.0, 1e-12);
  EXPECT_THROW(simplex_plane_slice(v, Plane{Eigen::Vector3d::Zero(), 0.0}, {}), InvalidInput);
}


// Slices sample like isosurfaces: by default local bisection, so on the clustered domain (small
// and large tetrahedra side by side) several planes through one bisection are exact (every vertex
// on its plane, carrying the linear attribute's value, the cut square's area 1) and cut far fewer
// tetrahedra than uniform refinement to the same finest edge; k > 0 cuts k³ per tetrahedron.
TEST(SimplexSlices, LocalBisectionOnAClusteredDomainIsExactAndCheaperThanUniform) {
  TetrahedralMesh domain = test_support::clustered_cube_domain();
  const std::size_t domain_tetrahedra = domain.tetrahedra.size();
  const double longest = longest_edge_length(domain);
  KnotClouds clouds = generate_knot_clouds(domain, 2);
  DmsSplineVolume v(std::move(domain), std::move(clouds), DmsControlSharing::Shared, {"density"});
  const Eigen::Vector3d a(-0.3, 0.8, 1.5);
  set_column_from_blossom(v, 3, [&](std::span<const Eigen::Vector3d> args) { return a.dot((args[0] + args[1]) / 2) - 0.1; });
  SimplexSliceOptions options;
  options.target_edge = 0.1;
  const std::vector<Plane> planes{Plane{Eigen::Vector3d(0, 1, 0), 0.25}, Plane{Eigen::Vector3d(1, 0, 0), 0.6}, Plane{Eigen::Vector3d(0, 0, -2), -0.2}};
  const std::vector<SimplexSlice> slices = simplex_plane_slices(v, planes, options);
  ASSERT_EQ(slices.size(), planes.size());
  const auto k = static_cast<long long>(std::ceil(longest / options.target_edge));
  for (std::size_t p = 0; p < planes.size(); ++p) {
    const SimplexSlice& slice = slices[p];
    EXPECT_EQ(slice.subdivisions, 0);
    ASSERT_GT(slice.mesh.num_triangles(), 20u);
    const Eigen::Vector3d n = planes[p].normal.normalized();
    const double d = planes[p].offset / planes[p].normal.norm();
    for (std::size_t i = 0; i < slice.mesh.num_vertices(); ++i) {
      // The domain point on the plane exactly; the geometry and the attribute reproduced (to the
      // accuracy of the basis on this domain's slivers).
      const Eigen::Vector3d& x = slice.mesh.parameters[i];
      EXPECT_NEAR(n.dot(x), d, 1e-12);
      EXPECT_NEAR((slice.mesh.positions[i] - x).norm(), 0.0, 1e-8);
      EXPECT_NEAR(slice.values[i], a.dot(x) - 0.1, 1e-7);
    }
    EXPECT_NEAR(surface_area(slice.mesh), 1.0, 1e-7);
    EXPECT_LT(4 * slice.sampled_tetrahedra, k * k * k * static_cast<long long>(domain_tetrahedra));
  }
  options.subdivisions = 2;
  const SimplexSlice uniform = simplex_plane_slice(v, planes[0], options);
  EXPECT_EQ(uniform.subdivisions, 2);
  EXPECT_EQ(uniform.sampled_tetrahedra, 8 * static_cast<long long>(domain_tetrahedra));
  EXPECT_NEAR(surface_area(uniform.mesh), 1.0, 1e-7);
  options.subdivisions = 65;
  EXPECT_THROW(simplex_plane_slice(v, planes[0], options), InvalidInput);
  options.subdivisions = 0;
  options.target_edge = -1;
  EXPECT_THROW(simplex_plane_slice(v, planes[0], options), InvalidInput);
  EXPECT_TRUE(simplex_plane_slices(v, {}, {}).empty());
}

}  // namespace
}  // namespace volspline
