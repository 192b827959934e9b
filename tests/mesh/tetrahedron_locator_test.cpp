#include "volspline/mesh/tetrahedron_locator.h"

#include <random>

#include <Eigen/LU>
#include <gtest/gtest.h>

#include "support/tetrahedral_domains.h"

namespace volspline {
namespace {

bool inside_closed_unit_cube(const Eigen::Vector3d& x) {
  return (x.array() >= 0).all() && (x.array() <= 1).all();
}

TEST(TetrahedronLocator, FindsTheTetrahedronHoldingAPointExactly) {
  const TetrahedralMesh cube = test_support::delaunay_cube(4);
  const TetrahedronLocator locator(cube);
  std::mt19937 random(2);
  std::uniform_real_distribution<double> u(-0.2, 1.2);
  for (int i = 0; i < 500; ++i) {
    const Eigen::Vector3d x(u(random), u(random), u(random));
    const int t = locator.locate(x);
    // Independent answer where it is unique: the tetrahedron with all barycentric coordinates
    // clearly positive.
    int strictly_inside = -1;
    for (std::size_t k = 0; k < cube.tetrahedra.size(); ++k) {
      const auto& tet = cube.tetrahedra[k];
      Eigen::Matrix3d m;
      for (int c = 0; c < 3; ++c) m.col(c) = cube.points[tet[c + 1]] - cube.points[tet[0]];
      const Eigen::Vector3d b = m.inverse() * (x - cube.points[tet[0]]);
      if ((b.array() > 1e-9).all() && b.sum() < 1 - 1e-9) strictly_inside = static_cast<int>(k);
    }
    if (strictly_inside >= 0) {
      EXPECT_EQ(t, strictly_inside) << x.transpose();
    }
    EXPECT_EQ(t >= 0, inside_closed_unit_cube(x)) << x.transpose();
  }
  // Vertices and faces belong to Ω.
  for (const auto& p : cube.points) EXPECT_GE(locator.locate(p), 0);
  EXPECT_GE(locator.locate({0.5, 0.5, 1.0}), 0);
  EXPECT_EQ(locator.locate({0.5, 0.5, std::nextafter(1.0, 2.0)}), -1);
}

}  // namespace
}  // namespace volspline
