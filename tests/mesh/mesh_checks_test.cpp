#include "volspline/mesh/mesh_checks.h"

#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

#include <gtest/gtest.h>

#include "support/test_meshes.h"
#include "volspline/core/error.h"

namespace volspline {
namespace {

// Eigen leaves `{}` uninitialised, so parameters that do not matter are spelled out.
const Eigen::Vector3d kNoParameter = Eigen::Vector3d::Zero();

TriangleMesh translated(TriangleMesh mesh, const Eigen::Vector3d& offset) {
  for (auto& p : mesh.positions) p += offset;
  return mesh;
}

TriangleMesh flipped(TriangleMesh mesh) {
  for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
  return mesh;
}

TEST(EdgeStatistics, ClosedCubeHas18ManifoldConsistentEdges) {
  const EdgeStatistics s = edge_statistics(test_support::unit_cube());
  EXPECT_EQ(s.edges, 18u);  // 12 cube edges + 6 face diagonals
  EXPECT_EQ(s.manifold_edges, 18u);
  EXPECT_EQ(s.boundary_edges, 0u);
  EXPECT_EQ(s.nonmanifold_edges, 0u);
  EXPECT_EQ(s.inconsistently_oriented_edges, 0u);
  EXPECT_TRUE(s.closed());
  EXPECT_TRUE(s.closed_and_oriented());
}

TEST(EdgeStatistics, CubeMinusATriangleHasThreeBoundaryEdges) {
  TriangleMesh cube = test_support::unit_cube();
  cube.triangles.pop_back();
  cube.parts.pop_back();
  const EdgeStatistics s = edge_statistics(cube);
  EXPECT_EQ(s.boundary_edges, 3u);
  EXPECT_EQ(s.edges, 18u);
  EXPECT_EQ(s.manifold_edges, 15u);
  EXPECT_FALSE(s.closed());
}

TEST(EdgeStatistics, OneFlippedTriangleMakesItsThreeEdgesInconsistent) {
  TriangleMesh cube = test_support::unit_cube();
  std::swap(cube.triangles[5][0], cube.triangles[5][1]);
  const EdgeStatistics s = edge_statistics(cube);
  EXPECT_TRUE(s.closed());
  EXPECT_EQ(s.inconsistently_oriented_edges, 3u);
  EXPECT_FALSE(s.closed_and_oriented());
}

TEST(EdgeStatistics, ThreeTrianglesOnOneEdgeAreNonmanifold) {
  TriangleMesh fan;
  fan.add_vertex({0, 0, 0}, kNoParameter);
  fan.add_vertex({1, 0, 0}, kNoParameter);
  for (int i = 0; i < 3; ++i) {
    const double angle = 2 * std::numbers::pi * i / 3;
    const int apex = fan.add_vertex({0.5, std::cos(angle), std::sin(angle)}, kNoParameter);
    fan.add_triangle(0, 1, apex, 0);
  }
  const EdgeStatistics s = edge_statistics(fan);
  EXPECT_EQ(s.edges, 7u);
  EXPECT_EQ(s.nonmanifold_edges, 1u);
  EXPECT_EQ(s.boundary_edges, 6u);
  EXPECT_FALSE(s.closed());
}

TEST(NonmanifoldVertices, ClosedCubeAndAnOpenDiskHaveNone) {
  EXPECT_EQ(nonmanifold_vertices(test_support::unit_cube()), 0u);
  TriangleMesh cube = test_support::unit_cube();
  cube.triangles.pop_back();
  cube.parts.pop_back();
  EXPECT_EQ(nonmanifold_vertices(cube), 0u);  // the hole's corners are on half-disks
}

TEST(NonmanifoldVertices, TwoCubesTouchingAtACornerMakeThatCornerNonmanifold) {
  // Closed and oriented edge by edge, yet not a 2-manifold: the shared corner's triangles form
  // two fans. Welding the copies' coincident corner gives exactly one such vertex.
  TriangleMesh two = test_support::unit_cube();
  const TriangleMesh other = translated(test_support::unit_cube(), {1, 1, 1});
  const auto base = static_cast<int>(two.num_vertices());
  for (std::size_t v = 0; v < other.num_vertices(); ++v) two.add_vertex(other.positions[v], kNoParameter);
  for (std::size_t f = 0; f < other.num_triangles(); ++f)
    two.add_triangle(other.triangles[f][0] + base, other.triangles[f][1] + base, other.triangles[f][2] + base, 0);
  EXPECT_EQ(nonmanifold_vertices(two), 0u);
  weld_by_position(two, 0);
  EXPECT_TRUE(edge_statistics(two).closed_and_oriented());
  EXPECT_EQ(nonmanifold_vertices(two), 1u);
}

// The count is made over blocks of vertices in parallel: a chain of 1,000 cubes (8,000 vertices,
// many blocks), each touching the next at a corner, has one such vertex per touch.
TEST(NonmanifoldVertices, AChainOfCubesTouchingAtCornersCountsEveryTouch) {
  TriangleMesh chain;
  const int cubes = 1000;
  for (int c = 0; c < cubes; ++c) chain.append(translated(test_support::unit_cube(), {double(c), double(c), double(c)}));
  EXPECT_EQ(nonmanifold_vertices(chain), 0u);
  weld_by_position(chain, 0);
  EXPECT_TRUE(edge_statistics(chain).closed_and_oriented());
  EXPECT_EQ(nonmanifold_vertices(chain), static_cast<std::size_t>(cubes - 1));
}

TEST(NonmanifoldVertices, ATriangleWithARepeatedCornerCountsItsCorners) {
  TriangleMesh mesh;
  mesh.add_vertex({0, 0, 0}, kNoParameter);
  mesh.add_vertex({1, 0, 0}, kNoParameter);
  mesh.add_triangle(0, 1, 1, 0);
  EXPECT_EQ(nonmanifold_vertices(mesh), 2u);
}

TEST(EdgeStatistics, EmptyMeshIsNotClosed) {
  const EdgeStatistics s = edge_statistics(TriangleMesh{});
  EXPECT_EQ(s.edges, 0u);
  EXPECT_FALSE(s.closed());
}

TEST(EdgeStatistics, SphereSatisfiesEulersFormula) {
  for (int levels = 0; levels <= 3; ++levels) {
    const TriangleMesh sphere = test_support::icosphere(levels);
    const EdgeStatistics s = edge_statistics(sphere);
    EXPECT_TRUE(s.closed_and_oriented());
    EXPECT_EQ(static_cast<long>(sphere.num_vertices()) - static_cast<long>(s.edges) +
                  static_cast<long>(sphere.num_triangles()),
              2);
  }
}

TEST(EdgeStatistics, MalformedMeshIsRejected) {
  TriangleMesh cube = test_support::unit_cube();
  cube.triangles[0][2] = -1;
  EXPECT_THROW(edge_statistics(cube), InvalidInput);
}

TEST(Measures, UnitCubeHasVolumeOneAndAreaSix) {
  EXPECT_DOUBLE_EQ(enclosed_volume(test_support::unit_cube()), 1.0);
  EXPECT_DOUBLE_EQ(surface_area(test_support::unit_cube()), 6.0);
  EXPECT_DOUBLE_EQ(enclosed_volume(flipped(test_support::unit_cube())), -1.0);
}

TEST(Measures, TetrahedronHasVolumeOneSixth) {
  EXPECT_DOUBLE_EQ(enclosed_volume(test_support::unit_tetrahedron()), 1.0 / 6);
  EXPECT_DOUBLE_EQ(surface_area(test_support::unit_tetrahedron()), 1.5 + std::sqrt(3.0) / 2);
}

TEST(Measures, VolumeDoesNotDependOnWhereTheMeshIs) {
  // Far from the origin the triple products of the raw coordinates are ~1e21 each; a volume of
  // 1 survives only if the computation is done relative to the mesh.
  const TriangleMesh far = translated(test_support::unit_cube(), {1e7, -3e7, 2e7});
  EXPECT_NEAR(enclosed_volume(far), 1.0, 1e-9);
  EXPECT_NEAR(surface_area(far), 6.0, 1e-8);
}

TEST(Measures, SphereApproachesTheBallFromInside) {
  double previous = 0;
  for (int levels = 0; levels <= 4; ++levels) {
    const double volume = enclosed_volume(test_support::icosphere(levels));
    EXPECT_GT(volume, previous);                  // refining adds volume ...
    EXPECT_LT(volume, 4 * std::numbers::pi / 3);  // ... but an inscribed polyhedron stays inside
    previous = volume;
  }
  EXPECT_NEAR(previous, 4 * std::numbers::pi / 3, 0.01);
  EXPECT_NEAR(surface_area(test_support::icosphere(4)), 4 * std::numbers::pi, 0.02);
}

TEST(Measures, EmptyMeshHasNothing) {
  EXPECT_EQ(enclosed_volume(TriangleMesh{}), 0.0);
  EXPECT_EQ(surface_area(TriangleMesh{}), 0.0);
}

TEST(Weld, SeparateQuadsOfACubeBecomeAClosedCubeWithEightVertices) {
  TriangleMesh cube = test_support::unit_cube_as_separate_quads();
  ASSERT_EQ(cube.num_vertices(), 24u);
  EXPECT_EQ(edge_statistics(cube).boundary_edges, 24u);
  weld_by_position(cube, 1e-9);
  EXPECT_EQ(cube.num_vertices(), 8u);
  EXPECT_EQ(cube.num_triangles(), 12u);
  EXPECT_EQ(cube.parameters.size(), 8u);
  EXPECT_TRUE(edge_statistics(cube).closed_and_oriented());
  EXPECT_DOUBLE_EQ(enclosed_volume(cube), 1.0);
  EXPECT_EQ(cube.parts, test_support::unit_cube().parts);
}

TEST(Weld, ExactModeMergesOnlyEqualPositions) {
  TriangleMesh cube = test_support::unit_cube_as_separate_quads();
  cube.positions[5].x() += 1e-12;  // one copy of a corner moved off by a hair
  weld_by_position(cube, 0);
  EXPECT_EQ(cube.num_vertices(), 9u);
  EXPECT_FALSE(edge_statistics(cube).closed());
}

TEST(Weld, ToleranceBridgesSmallGapsAndKeepsTheFirstVertex) {
  TriangleMesh cube = test_support::unit_cube_as_separate_quads();
  for (std::size_t v = 0; v < cube.num_vertices(); ++v) {
    cube.positions[v] += Eigen::Vector3d::Constant(1e-7 * static_cast<double>(v % 3));
    cube.parameters[v] = Eigen::Vector3d::Constant(static_cast<double>(v));
  }
  const TriangleMesh before = cube;
  weld_by_position(cube, 1e-5);
  ASSERT_EQ(cube.num_vertices(), 8u);
  EXPECT_TRUE(edge_statistics(cube).closed_and_oriented());
  // Every survivor is the first of its copies: its position and parameters are those of the
  // lowest-numbered input vertex at that corner.
  for (std::size_t v = 0; v < cube.num_vertices(); ++v) {
    std::size_t first = before.num_vertices();
    for (std::size_t w = 0; w < before.num_vertices() && first == before.num_vertices(); ++w) {
      if ((before.positions[w] - cube.positions[v]).norm() <= 1e-5) first = w;
    }
    ASSERT_LT(first, before.num_vertices());
    EXPECT_EQ(cube.positions[v], before.positions[first]);
    EXPECT_EQ(cube.parameters[v], before.parameters[first]);
  }
}

TEST(Weld, DropsTrianglesThatCollapseAndVerticesNobodyUses) {
  TriangleMesh mesh = test_support::unit_cube();
  // A sliver whose two nearby corners merge, and a vertex no triangle uses.
  const int a = mesh.add_vertex({2, 0, 0}, kNoParameter);
  const int b = mesh.add_vertex({2, 1e-8, 0}, kNoParameter);
  const int c = mesh.add_vertex({2, 0, 1}, kNoParameter);
  mesh.add_vertex({5, 5, 5}, kNoParameter);
  mesh.add_triangle(a, b, c, Part::JacobianZero);
  weld_by_position(mesh, 1e-6);
  EXPECT_EQ(mesh.num_triangles(), 12u);
  EXPECT_EQ(mesh.num_vertices(), 8u);
  EXPECT_EQ(mesh.positions, test_support::unit_cube().positions);
  EXPECT_EQ(mesh.triangles, test_support::unit_cube().triangles);
}

TEST(Weld, WorksFarFromTheOriginAndWithHugeCoordinates) {
  TriangleMesh far = translated(test_support::unit_cube_as_separate_quads(), {1e12, 0, -1e12});
  weld_by_position(far, 0);
  EXPECT_EQ(far.num_vertices(), 8u);
  TriangleMesh huge = test_support::unit_cube_as_separate_quads();
  for (auto& p : huge.positions) p *= 1e300;
  weld_by_position(huge, 1e-9);
  EXPECT_EQ(huge.num_vertices(), 8u);
}

TEST(Weld, RejectsBadTolerances) {
  TriangleMesh cube = test_support::unit_cube();
  EXPECT_THROW(weld_by_position(cube, -1e-9), InvalidInput);
  EXPECT_THROW(weld_by_position(cube, std::numeric_limits<double>::quiet_NaN()), InvalidInput);
  EXPECT_THROW(weld_by_position(cube, std::numeric_limits<double>::infinity()), InvalidInput);
  EXPECT_EQ(cube.num_vertices(), 8u);
}

}  // namespace
}  // namespace volspline
