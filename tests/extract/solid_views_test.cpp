// solid_view_mesh and the planes of a request: what is asked for and nothing else — each family
// of isoparametric surfaces on its own part with the constant parameter, every slice vertex on its
// plane and in the solid, faces cut back to the wedge's walls — with every vertex the image of its
// parameters.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "volspline/construct/example_solids.h"
#include "volspline/construct/primitives.h"
#include "volspline/core/error.h"
#include "volspline/extract/solid_views.h"

namespace volspline {
namespace {

// Every vertex is the volume at its parameters.
void expect_vertices_on_the_solid(const BSplineVolume& volume, const TriangleMesh& mesh) {
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    const Eigen::Vector3d& t = mesh.parameters[v];
    const Eigen::VectorXd x = volume.evaluate({t.x(), t.y(), t.z()});
    EXPECT_LT((x - mesh.positions[v]).norm(), 1e-9) << v;
  }
}

// normal·x - offset: positive on the plane's positive side.
double signed_distance(const Plane& plane, const Eigen::Vector3d& x) { return plane.normal.dot(x) - plane.offset; }

std::set<int> parts_of(const TriangleMesh& mesh) { return {mesh.parts.begin(), mesh.parts.end()}; }

TEST(SolidViews, AFamilyIsItsSurfacesAtEvenlySpacedParameters) {
  const BSplineVolume volume = bent_tricubic_volume();
  SolidViewRequest request;
  request.families = {{1, 3}};
  request.resolution = 6;
  EXPECT_FALSE(request.probes_empty());
  const TriangleMesh mesh = solid_view_mesh(volume, request, {});
  ASSERT_GT(mesh.num_triangles(), 0u);
  EXPECT_EQ(parts_of(mesh), (std::set<int>{8}));
  std::set<double> values;
  for (const auto& t : mesh.parameters) values.insert(t.y());
  const double a = volume.domain_min(1), b = volume.domain_max(1);
  EXPECT_EQ(values, (std::set<double>{a, a + 0.5 * (b - a), b}));
  expect_vertices_on_the_solid(volume, mesh);
}

TEST(SolidViews, ThroughAPointGivesTheThreeSurfacesThroughIt) {
  const BSplineVolume volume = bent_tricubic_volume();
  SolidViewRequest request;
  request.through = std::array<double, 3>{0.3, 0.6, 0.5};
  request.resolution = 6;
  const TriangleMesh mesh = solid_view_mesh(volume, request, {});
  EXPECT_EQ(parts_of(mesh), (std::set<int>{7, 8, 9}));
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    const int d = mesh.parts[i] - 7;
    for (const int v : mesh.triangles[i]) EXPECT_EQ(mesh.parameters[static_cast<std::size_t>(v)][d], request.through->at(static_cast<std::size_t>(d)));
  }
  expect_vertices_on_the_solid(volume, mesh);
}

TEST(SolidViews, SlicesLieOnTheirPlanesAndFacesAreAddedOnRequest) {
  const BSplineVolume volume = torus(3.0, 1.0, 270.0);
  SolidViewRequest request;
  request.series = {{2, 3}};
  request.resolution = 8;
  const auto [lo, hi] = sampled_bounding_box(volume);
  const std::vector<Plane> planes = requested_planes(request, lo, hi);
  ASSERT_EQ(planes.size(), 3u);
  const TriangleMesh slices = solid_view_mesh(volume, request, planes);
  ASSERT_GT(slices.num_triangles(), 0u);
  EXPECT_EQ(parts_of(slices), (std::set<int>{10}));
  for (const auto& x : slices.positions) {
    const double distance = std::min({std::abs(signed_distance(planes[0], x)), std::abs(signed_distance(planes[1], x)),
                                      std::abs(signed_distance(planes[2], x))});
    EXPECT_LT(distance, 1e-9);
  }
  expect_vertices_on_the_solid(volume, slices);
  request.faces = true;
  const TriangleMesh both = solid_view_mesh(volume, request, planes);
  // The torus's u = min face is its tube's centre line, collapsed away; the others are there.
  EXPECT_EQ(parts_of(both), (std::set<int>{1, 2, 3, 4, 5, 10}));
  EXPECT_GT(both.num_triangles(), slices.num_triangles());
}

TEST(SolidViews, ACutawayRemovesTheWedgeAndKeepsItsWalls) {
  const BSplineVolume volume = box(Eigen::Vector3d(2, 2, 2));
  SolidViewRequest request;
  request.core = Eigen::Vector3d(0.2, -0.1, 0.3);
  request.cutaway = true;
  request.resolution = 8;
  EXPECT_FALSE(request.probes_empty());
  const std::vector<Plane> cuts = cut_planes(request);
  ASSERT_EQ(cuts.size(), 3u);
  const auto [lo, hi] = sampled_bounding_box(volume);
  const TriangleMesh mesh = solid_view_mesh(volume, request, requested_planes(request, lo, hi));
  EXPECT_TRUE(parts_of(mesh).count(10));
  // No triangle lies strictly inside the wedge (on the positive side of all three planes).
  for (const auto& triangle : mesh.triangles) {
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (const int v : triangle) centroid += mesh.positions[static_cast<std::size_t>(v)] / 3.0;
    const bool inside = std::all_of(cuts.begin(), cuts.end(), [&](const Plane& p) { return signed_distance(p, centroid) > 1e-9; });
    EXPECT_FALSE(inside);
  }
  // The walls: every slice vertex on one of the planes and on no plane's negative side.
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    if (mesh.parts[i] != 10) continue;
    for (const int v : mesh.triangles[i]) {
      const Eigen::Vector3d& x = mesh.positions[static_cast<std::size_t>(v)];
      const auto on = std::count_if(cuts.begin(), cuts.end(), [&](const Plane& p) { return std::abs(signed_distance(p, x)) < 1e-9; });
      EXPECT_GE(on, 1);
      for (const Plane& p : cuts) EXPECT_GT(signed_distance(p, x), -1e-9);
    }
  }
  expect_vertices_on_the_solid(volume, mesh);
}

TEST(SolidViews, NothingButFacesWhenNothingInsideIsAsked) {
  SolidViewRequest request;
  EXPECT_TRUE(request.probes_empty());
  request.faces = true;
  request.resolution = 4;
  const TriangleMesh mesh = solid_view_mesh(box(Eigen::Vector3d(1, 2, 3)), request, {});
  EXPECT_EQ(parts_of(mesh), (std::set<int>{0, 1, 2, 3, 4, 5}));
  EXPECT_TRUE(cut_planes(request).empty());
}

TEST(SolidViews, RequestedPlanesAreNormalisedAndBadRequestsRejected) {
  SolidViewRequest request;
  request.planes = {{Eigen::Vector3d(0, 0, 2), 1.0}};
  request.paddlewheels = {{2, 4, std::nullopt}};
  const std::vector<Plane> planes = requested_planes(request, Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(3, 1, 1));
  ASSERT_EQ(planes.size(), 5u);
  EXPECT_EQ(planes[0].normal, Eigen::Vector3d(0, 0, 1));
  EXPECT_EQ(planes[0].offset, 0.5);
  // The paddlewheel's planes contain its axis, the z line through the box's centre (1, 0, 0).
  for (std::size_t i = 1; i < planes.size(); ++i) {
    EXPECT_NEAR(planes[i].normal.z(), 0.0, 1e-15);
    EXPECT_NEAR(signed_distance(planes[i], Eigen::Vector3d(1, 0, 5)), 0.0, 1e-12);
  }
  request.paddlewheels = {{3, 4, std::nullopt}};
  EXPECT_THROW(requested_planes(request, Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones()), InvalidInput);
  request.paddlewheels.clear();
  request.planes = {{Eigen::Vector3d::Zero(), 1.0}};
  EXPECT_THROW(requested_planes(request, Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones()), InvalidInput);
}

}  // namespace
}  // namespace volspline
