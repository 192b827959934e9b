#include "volspline/mesh/mesh_clipping.h"

#include <map>

#include <gtest/gtest.h>

#include "support/test_meshes.h"
#include "volspline/core/error.h"
#include "volspline/mesh/mesh_checks.h"

namespace volspline {
namespace {

std::map<std::pair<int, int>, int> edge_uses(const TriangleMesh& m) {
  std::map<std::pair<int, int>, int> uses;
  for (const auto& t : m.triangles)
    for (int i = 0; i < 3; ++i) ++uses[{std::min(t[i], t[(i + 1) % 3]), std::max(t[i], t[(i + 1) % 3])}];
  return uses;
}

TEST(MeshClipping, TheTwoPartsPartitionTheSurface) {
  const TriangleMesh sphere = test_support::icosphere(3);
  const std::vector<Plane> octant{plane_through(Eigen::Vector3d(0.1, 0, 0), Eigen::Vector3d::UnitX()),
                                  plane_through(Eigen::Vector3d(0, -0.2, 0), Eigen::Vector3d::UnitY()),
                                  plane_through(Eigen::Vector3d(0, 0, 0.3), Eigen::Vector3d(0.2, 0, 1))};
  for (std::size_t count = 1; count <= 3; ++count) {
    const std::vector<Plane> planes(octant.begin(), octant.begin() + static_cast<std::ptrdiff_t>(count));
    const TriangleMesh outside = remove_convex_region(sphere, planes), inside = keep_convex_region(sphere, planes);
    EXPECT_NEAR(surface_area(outside) + surface_area(inside), surface_area(sphere), 1e-12 * surface_area(sphere));
    EXPECT_GT(surface_area(inside), 0.01);
    for (const auto& p : inside.positions)
      for (const auto& plane : planes) EXPECT_GE(plane.normal.dot(p) - plane.offset, -1e-15);
    // Every triangle outside has its centroid on the negative side of some plane.
    for (const auto& t : outside.triangles) {
      const Eigen::Vector3d c = (outside.positions[t[0]] + outside.positions[t[1]] + outside.positions[t[2]]) / 3;
      bool negative = false;
      for (const auto& plane : planes) negative = negative || plane.normal.dot(c) - plane.offset <= 0;
      EXPECT_TRUE(negative);
    }
  }
}

TEST(MeshClipping, CutsAClosedSurfaceWithoutCracksAlongThePlane) {
  const TriangleMesh sphere = test_support::icosphere(3);
  const Plane plane = plane_through(Eigen::Vector3d(0, 0, 0.25), Eigen::Vector3d(0.3, 0.1, 1));
  const TriangleMesh cut = remove_convex_region(sphere, {plane});
  int borders = 0;
  for (const auto& [edge, count] : edge_uses(cut)) {
    ASSERT_LE(count, 2);
    if (count == 1) {
      ++borders;
      EXPECT_NEAR(plane.normal.dot(cut.positions[static_cast<std::size_t>(edge.first)]), plane.offset, 1e-14);
      EXPECT_NEAR(plane.normal.dot(cut.positions[static_cast<std::size_t>(edge.second)]), plane.offset, 1e-14);
    }
  }
  EXPECT_GT(borders, 10);
}

TEST(MeshClipping, FacesInACutPlaneAreKeptOnceAndBadPlanesAreRejected) {
  const TriangleMesh cube = test_support::unit_cube();
  const auto [lo, hi] = cube.bounding_box();
  // The plane through the cube's top face: nothing lies on its open positive side.
  const Plane top{Eigen::Vector3d::UnitZ(), hi.z()};
  const TriangleMesh same = remove_convex_region(cube, {top});
  EXPECT_EQ(same.num_triangles(), cube.num_triangles());
  EXPECT_NEAR(surface_area(same), surface_area(cube), 1e-14);
  EXPECT_EQ(keep_convex_region(cube, {top}).num_triangles(), 0u);
  (void)lo;
  EXPECT_THROW(remove_convex_region(cube, {{Eigen::Vector3d::Zero(), 0.0}}), InvalidInput);
}

}  // namespace
}  // namespace volspline
