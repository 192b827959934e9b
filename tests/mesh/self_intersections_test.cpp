// Self-intersections by CGAL's exact predicates, and the same answers from a record of an earlier
// mesh that differs in a few triangles.
#include "volspline/mesh/self_intersections.h"

#include <gtest/gtest.h>

#include "support/test_meshes.h"

namespace volspline {
namespace {

TriangleMesh moved(TriangleMesh mesh, const Eigen::Vector3d& by) {
  for (Eigen::Vector3d& p : mesh.positions) p += by;
  return mesh;
}

// Three spheres (icospheres of 320 triangles, radius 1): A at the origin, B at distance `ab`
// from it along x, C far away along y.
TriangleMesh three_spheres(double ab) {
  const TriangleMesh sphere = test_support::icosphere(2);
  TriangleMesh mesh = sphere;
  mesh.append(moved(sphere, {ab, 0, 0}));
  mesh.append(moved(sphere, {0, 10, 0}));
  return mesh;
}

// Each pair (i, j) of triangles in `pairs` intersects and none outside does, checked
// independently: a pair of triangles of different spheres intersects only where the spheres
// overlap, and triangles of one convex sphere never do.
TEST(SelfIntersectingTriangles, SeparateSpheresHaveNoneOverlappingOnesHavePairsAcrossOnly) {
  const TriangleMesh apart = three_spheres(2.5);
  EXPECT_TRUE(self_intersecting_triangles(apart).empty());
  const TriangleMesh overlapping = three_spheres(1.5);
  const auto pairs = self_intersecting_triangles(overlapping);
  ASSERT_FALSE(pairs.empty());
  const std::size_t per_sphere = apart.num_triangles() / 3;
  for (const auto& [i, j] : pairs) {
    EXPECT_LT(i, j);
    EXPECT_LT(i, per_sphere) << "only A and B overlap";
    EXPECT_GE(j, per_sphere);
    EXPECT_LT(j, 2 * per_sphere);
  }
  EXPECT_TRUE(std::is_sorted(pairs.begin(), pairs.end()));
}

// With a record of an earlier mesh, the answer is the answer of a full test, and only the
// triangles near the ones that changed are tested again: the pairs between A and B, unchanged,
// come from the record while C moves into B.
TEST(SelfIntersectingTriangles, ARecordGivesTheFullAnswerTestingOnlyAroundTheChange) {
  SelfIntersectionRecord record;
  const TriangleMesh before = three_spheres(1.5);
  const auto first = self_intersecting_triangles(before, &record);
  EXPECT_EQ(first, self_intersecting_triangles(before));
  EXPECT_EQ(record.tested_triangles(), before.num_triangles()) << "nothing recorded yet: a full test";
  EXPECT_EQ(record.reused_triangles(), 0u);

  // The same mesh again: nothing is new, nothing is tested, the pairs are the recorded ones.
  EXPECT_EQ(self_intersecting_triangles(before, &record), first);
  EXPECT_EQ(record.tested_triangles(), 0u);

  // C moved into B: new pairs between B and C, A and B's pairs unchanged.
  TriangleMesh after = before;
  const std::size_t per_sphere = before.num_triangles() / 3;
  const std::size_t c_vertices = after.num_vertices() / 3;
  for (std::size_t v = 2 * c_vertices; v < after.num_vertices(); ++v) after.positions[v] += Eigen::Vector3d(2.2, -9.0, 0);
  const auto full = self_intersecting_triangles(after);
  const auto incremental = self_intersecting_triangles(after, &record);
  EXPECT_EQ(incremental, full);
  std::size_t across_bc = 0, across_ab = 0;
  for (const auto& [i, j] : full) {
    if (i >= per_sphere && j >= 2 * per_sphere) ++across_bc;
    if (i < per_sphere && j < 2 * per_sphere) ++across_ab;
  }
  EXPECT_GT(across_bc, 0u);
  EXPECT_EQ(across_ab, first.size());
  EXPECT_LT(record.tested_triangles(), 2 * per_sphere) << "A is far from every moved triangle";
  EXPECT_GT(record.reused_triangles(), per_sphere);

  // Moving C back removes its pairs, again as a full test finds.
  EXPECT_EQ(self_intersecting_triangles(before, &record), first);

  // A record moved elsewhere goes with its contents; the one moved from starts empty.
  SelfIntersectionRecord moved = std::move(record);
  EXPECT_EQ(self_intersecting_triangles(before, &moved), first);
  EXPECT_EQ(moved.tested_triangles(), 0u);
  EXPECT_EQ(self_intersecting_triangles(before, &record), first);
  EXPECT_EQ(record.tested_triangles(), before.num_triangles());
}

// Where two vertices share a position, whether two triangles touch depends on more than their
// corners: the record is not used (a full test), and the answer is still the full one.
TEST(SelfIntersectingTriangles, DuplicatePositionsTestEverything) {
  SelfIntersectionRecord record;
  TriangleMesh mesh = three_spheres(1.5);
  self_intersecting_triangles(mesh, &record);
  // Two cubes sharing a corner position as two distinct vertices (closed, oriented, manifold).
  TriangleMesh cubes = test_support::unit_cube();
  cubes.append(moved(test_support::unit_cube(), {1, 1, 1}));
  mesh.append(moved(cubes, {0, -10, 0}));
  const auto full = self_intersecting_triangles(mesh);
  EXPECT_EQ(self_intersecting_triangles(mesh, &record), full);
  EXPECT_EQ(record.tested_triangles(), mesh.num_triangles());
  EXPECT_EQ(self_intersecting_triangles(mesh, &record), full);
  EXPECT_EQ(record.tested_triangles(), mesh.num_triangles());
}

// A mesh of 20,000 triangles and more is tested in slabs along its longest axis, in parallel;
// the answer is CGAL's test of the whole mesh at once (what a record of an unrelated mesh makes
// it run: every triangle new), and the pairs lie across the two overlapping spheres only. The
// slabs' borders (at quantiles of the triangles' centres along y) cut through the overlap.
TEST(SelfIntersectingTriangles, ALargeMeshTestedInSlabsGivesTheWholeMeshsAnswer) {
  const TriangleMesh sphere = test_support::icosphere(4);
  TriangleMesh mesh = sphere;
  mesh.append(moved(sphere, {1.5, 0.3, 0}));
  mesh.append(moved(test_support::icosphere(5), {0, 10, 0}));
  ASSERT_GE(mesh.num_triangles(), 30000u);
  const auto slabbed = self_intersecting_triangles(mesh);
  SelfIntersectionRecord unrelated;
  self_intersecting_triangles(moved(test_support::unit_cube(), {0, 0, 50}), &unrelated);
  const auto whole = self_intersecting_triangles(mesh, &unrelated);
  EXPECT_EQ(unrelated.tested_triangles(), mesh.num_triangles());
  EXPECT_EQ(slabbed, whole);
  ASSERT_FALSE(slabbed.empty());
  const std::size_t per_sphere = sphere.num_triangles();
  for (const auto& [i, j] : slabbed) {
    EXPECT_LT(i, per_sphere);
    EXPECT_GE(j, per_sphere);
    EXPECT_LT(j, 2 * per_sphere);
  }
}

}  // namespace
}  // namespace volspline
