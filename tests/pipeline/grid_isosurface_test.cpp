#include "volspline/pipeline/grid_isosurface.h"

#include <cmath>
#include <numbers>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "volspline/construct/volume_data_examples.h"
#include "volspline/core/error.h"
#include "volspline/mesh/mesh_checks.h"

namespace volspline {
namespace {

RegularGridData grid_of(int n, double (*f)(const Eigen::Vector3d&)) {
  std::vector<Eigen::Vector3d> points;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) points.emplace_back(-1 + 2.0 * i / (n - 1), -1 + 2.0 * j / (n - 1), -1 + 2.0 * k / (n - 1));
  return *regular_grid_of(sampled_volume_data(points, "f", f));
}

// A linear field is linear on every tetrahedron: its isosurface is the plane itself.
TEST(GridIsosurface, ALinearFieldGivesItsPlaneExactly) {
  const RegularGridData grid = grid_of(9, [](const Eigen::Vector3d& x) { return x.x() + 2 * x.y() + 3 * x.z(); });
  const TriangleMesh mesh = grid_isosurface(grid, "f", 0.7);
  ASSERT_GT(mesh.num_triangles(), 0u);
  for (const auto& x : mesh.positions) EXPECT_NEAR(x.x() + 2 * x.y() + 3 * x.z(), 0.7, 1e-12) << x.transpose();
  // Oriented towards larger values: every triangle's normal along (1, 2, 3).
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d& a = mesh.positions[static_cast<std::size_t>(t[0])];
    const Eigen::Vector3d n = (mesh.positions[static_cast<std::size_t>(t[1])] - a).cross(mesh.positions[static_cast<std::size_t>(t[2])] - a);
    EXPECT_GT(n.dot(Eigen::Vector3d(1, 2, 3)), 0);
  }
}

// |x|^2 = 0.5 inside the box: a closed sphere of radius sqrt(0.5), its vertices on it to the
// linear interpolation's error (h^2 / 4 of the second derivative 2 over r), its volume close.
TEST(GridIsosurface, ASphereInsideTheGridIsClosedAndOnTheSphere) {
  const int n = 41;
  const double h = 2.0 / (n - 1), r = std::sqrt(0.5);
  const RegularGridData grid = grid_of(n, [](const Eigen::Vector3d& x) { return x.squaredNorm(); });
  const TriangleMesh mesh = grid_isosurface(grid, "f", 0.5);
  EXPECT_TRUE(edge_statistics(mesh).closed_and_oriented());
  for (const auto& x : mesh.positions) EXPECT_NEAR(x.norm(), r, h * h / r) << x.transpose();
  // Oriented towards larger |x|: outward, so the enclosed volume is positive.
  EXPECT_NEAR(enclosed_volume(mesh), 4.0 / 3 * std::numbers::pi * r * r * r, 0.01);
}

TEST(GridIsosurface, RefusesAnUnknownAttributeAndAnInfiniteValue) {
  const RegularGridData grid = grid_of(3, [](const Eigen::Vector3d& x) { return x.x(); });
  try {
    grid_isosurface(grid, "g", 0);
    ADD_FAILURE();
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("they have: f"), std::string::npos) << e.what();
  }
  EXPECT_THROW(grid_isosurface(grid, "f", std::nan("")), InvalidInput);
  EXPECT_EQ(grid_isosurface(grid, "f", 5).num_triangles(), 0u);
}

}  // namespace
}  // namespace volspline
