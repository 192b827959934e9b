// Marching tetrahedra on the 24-tetrahedra partition of a grid: a sphere's distance function gives
// a closed surface near the sphere, every triangle tagged with its cube's part, and grids whose
// parts or values do not match their size are refused.
#include "volspline/boxspline/lattice_isosurface.h"

#include <gtest/gtest.h>

#include <cmath>

#include "volspline/core/error.h"
#include "volspline/mesh/mesh_checks.h"

namespace volspline {
namespace {

// |x| - r at every partition vertex of a grid of n^3 cubes on [-1, 1]^3.
TetrahedralGrid sphere_grid(int n, double r) {
  TetrahedralGrid grid(Eigen::Vector3d(-1, -1, -1), 2.0 / n, {n, n, n});
  const auto nodes = grid.nodes();
  for (int c = 0; c < nodes[2]; ++c)
    for (int b = 0; b < nodes[1]; ++b)
      for (int a = 0; a < nodes[0]; ++a) grid.value(a, b, c) = grid.node_position(a, b, c).norm() - r;
  return grid;
}

TEST(LatticeIsosurface, SphereIsClosedAndTaggedByCube) {
  TetrahedralGrid grid = sphere_grid(8, 0.7);
  const TriangleMesh plain = march_tetrahedra(grid);
  ASSERT_GT(plain.num_triangles(), 100u);
  EXPECT_TRUE(edge_statistics(plain).closed_and_oriented());
  for (const int part : plain.parts) EXPECT_EQ(part, part_number(Part::BlendSpline));
  // Linear interpolation of a convex function: vertices lie on edges whose ends straddle the
  // sphere, so within one grid diagonal of it.
  for (const Eigen::Vector3d& x : plain.positions) EXPECT_LT(std::abs(x.norm() - 0.7), std::sqrt(3.0) * grid.spacing);

  // Cubes with x < 0 are the primitives': triangles follow their cube's part.
  grid.cube_parts.assign(512, Part::BlendSpline);
  for (int c = 0; c < 8; ++c)
    for (int b = 0; b < 8; ++b)
      for (int a = 0; a < 4; ++a) grid.cube_parts[static_cast<std::size_t>(a + 8 * (b + 8 * c))] = Part::BlendPrimitive;
  const TriangleMesh tagged = march_tetrahedra(grid);
  ASSERT_EQ(tagged.num_triangles(), plain.num_triangles());
  for (std::size_t t = 0; t < tagged.num_triangles(); ++t) {
    const auto& tri = tagged.triangles[t];
    const double x = (tagged.positions[tri[0]] + tagged.positions[tri[1]] + tagged.positions[tri[2]])[0] / 3.0;
    EXPECT_EQ(tagged.parts[t], part_number(x < 0 ? Part::BlendPrimitive : Part::BlendSpline)) << "triangle " << t;
  }
}

TEST(LatticeIsosurface, RefusesPartsOrValuesThatDoNotFitTheGrid) {
  TetrahedralGrid grid = sphere_grid(4, 0.5);
  grid.cube_parts.assign(63, Part::BlendSpline);
  EXPECT_THROW(march_tetrahedra(grid), InvalidInput);
  grid.cube_parts.clear();
  grid.values.pop_back();
  EXPECT_THROW(march_tetrahedra(grid), InvalidInput);
  EXPECT_THROW(TetrahedralGrid(Eigen::Vector3d::Zero(), 0.0, {1, 1, 1}), InvalidInput);
  EXPECT_THROW(TetrahedralGrid(Eigen::Vector3d::Zero(), 1.0, {1, 0, 1}), InvalidInput);
}

}  // namespace
}  // namespace volspline
