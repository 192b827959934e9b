#include "volspline/mesh/delaunay_tetrahedralization.h"

#include <random>

#include <Eigen/LU>

#include <gtest/gtest.h>

#include "support/tetrahedral_domains.h"
#include "volspline/core/error.h"
#include "volspline/mesh/mesh_checks.h"

namespace volspline {
namespace {

std::vector<Eigen::Vector3d> random_points(int count, std::uint32_t seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < count; ++i) points.emplace_back(u(random), u(random), u(random));
  return points;
}

// Circumcentre of a tetrahedron: solves 2 (x_k - a) . c' = |x_k - a|^2 for c' = c - a.
Eigen::Vector3d circumcentre(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                             const Eigen::Vector3d& d) {
  Eigen::Matrix3d m;
  m.row(0) = 2 * (b - a);
  m.row(1) = 2 * (c - a);
  m.row(2) = 2 * (d - a);
  const Eigen::Vector3d rhs((b - a).squaredNorm(), (c - a).squaredNorm(), (d - a).squaredNorm());
  return a + m.fullPivLu().solve(rhs);
}

TEST(DelaunayTetrahedralization, RandomPointsHaveEmptyCircumspheresAndFillTheHull) {
  const auto points = random_points(150, 3);
  const TetrahedralMesh mesh = delaunay_tetrahedralization(points);
  EXPECT_NO_THROW(validate_tetrahedral_mesh(mesh));
  ASSERT_EQ(mesh.points.size(), points.size());
  for (std::size_t i = 0; i < points.size(); ++i) EXPECT_EQ(mesh.points[i], points[i]);
  // Empty-sphere property: no point strictly inside any circumsphere (up to rounding of the
  // circumcentre, relative 1e-9).
  for (const auto& t : mesh.tetrahedra) {
    const Eigen::Vector3d c = circumcentre(points[t[0]], points[t[1]], points[t[2]], points[t[3]]);
    const double r2 = (points[t[0]] - c).squaredNorm();
    for (const auto& p : points) EXPECT_GE((p - c).squaredNorm(), r2 * (1 - 1e-9));
  }
  // The boundary is closed and its volume is that of the tetrahedra.
  const TriangleMesh surface = test_support::boundary_surface(mesh);
  EXPECT_TRUE(edge_statistics(surface).closed_and_oriented());
  EXPECT_NEAR(enclosed_volume(surface), tetrahedral_mesh_volume(mesh), 1e-12);
}

TEST(DelaunayTetrahedralization, ResultDoesNotDependOnThePointOrder) {
  auto points = random_points(60, 11);
  const TetrahedralMesh first = delaunay_tetrahedralization(points);
  // Reverse the points and map the tetrahedra back.
  std::vector<Eigen::Vector3d> reversed(points.rbegin(), points.rend());
  TetrahedralMesh second = delaunay_tetrahedralization(reversed);
  const int n = static_cast<int>(points.size());
  std::vector<std::array<int, 4>> mapped;
  for (auto t : second.tetrahedra) {
    for (int& v : t) v = n - 1 - v;
    std::sort(t.begin(), t.end());
    mapped.push_back(t);
  }
  std::vector<std::array<int, 4>> original;
  for (auto t : first.tetrahedra) {
    std::sort(t.begin(), t.end());
    original.push_back(t);
  }
  std::sort(mapped.begin(), mapped.end());
  std::sort(original.begin(), original.end());
  EXPECT_EQ(mapped, original);
}

TEST(DelaunayTetrahedralization, GridCubeHasVolumeOne) {
  const TetrahedralMesh cube = test_support::delaunay_cube(4, 0.0);  // cospherical points everywhere
  EXPECT_NO_THROW(validate_tetrahedral_mesh(cube));
  EXPECT_NEAR(tetrahedral_mesh_volume(cube), 1.0, 1e-14);
}

TEST(DelaunayTetrahedralization, RejectsWhatCannotBeTetrahedralised) {
  const auto expect_invalid = [](const std::vector<Eigen::Vector3d>& points, const std::string& where,
                                 const std::string& part) {
    try {
      delaunay_tetrahedralization(points);
      ADD_FAILURE() << "no InvalidInput";
    } catch (const InvalidInput& e) {
      EXPECT_EQ(e.where(), where) << e.what();
      EXPECT_NE(e.message().find(part), std::string::npos) << e.what();
    }
  };
  expect_invalid({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, "points", "at least 4");
  expect_invalid({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0.3, 0.2, 0}}, "points", "coplanar");
  expect_invalid({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 0}}, "points[4]", "duplicate of points[1]");
  expect_invalid({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, std::nan("")}}, "points[3]", "not finite");
}

}  // namespace
}  // namespace volspline
