#include "volspline/mesh/interface_split.h"

#include <map>

#include <gtest/gtest.h>

#include "support/tetrahedral_domains.h"
#include "volspline/core/error.h"

namespace volspline {
namespace {

// The plane x + 0.3 y = 0.55 as a signed distance and its unit normal.
const Eigen::Vector3d kSplitNormal = Eigen::Vector3d(1, 0.3, 0).normalized();
double split_plane_level(const Eigen::Vector3d& x) { return kSplitNormal.dot(x - Eigen::Vector3d(0.55, 0, 0)); }

double split_piece_volume(const TetrahedralMesh& mesh, const std::array<int, 4>& t) {
  const auto& p = mesh.points;
  return (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]).dot(p[t[3]] - p[t[0]]) / 6;
}

InterfaceSplit split_cube(const TetrahedralMesh& cube, double snap) {
  std::vector<double> level;
  std::vector<Eigen::Vector3d> normal;
  for (const Eigen::Vector3d& p : cube.points) {
    level.push_back(split_plane_level(p));
    normal.push_back(kSplitNormal);
  }
  InterfaceSplitOptions options;
  options.snap = snap;
  return split_at_interface(cube, level, normal, options);
}

TEST(InterfaceSplit, PiecesTileEachSideOfAPlaneExactlyAndTheSidesShareNoPoint) {
  const TetrahedralMesh cube = test_support::delaunay_cube(5);
  for (double snap : {0.0, 0.25}) {
    const InterfaceSplit split = split_cube(cube, snap);
    ASSERT_NO_THROW(validate_tetrahedral_mesh(split.mesh)) << "snap " << snap;
    EXPECT_GT(split.cut_tetrahedra, 0u);
    if (snap > 0) {
      EXPECT_GT(split.snapped_points, 0u);
    }
    // {x + 0.3 y < 0.55} ∩ [0, 1]³ has volume ∫ (0.55 − 0.3 y) dy = 0.4; the plane is the
    // level's exact zero set, so the pieces reproduce it to rounding.
    std::array<double, 2> volume{0, 0};
    for (std::size_t t = 0; t < split.side.size(); ++t) {
      const auto& tet = split.mesh.tetrahedra[t];
      volume[static_cast<std::size_t>(split.side[t])] += split_piece_volume(split.mesh, tet);
      for (int v : tet) {
        const double level = split_plane_level(split.mesh.points[static_cast<std::size_t>(v)]);
        if (split.side[t] == 0) {
          EXPECT_LE(level, 1e-12);
        } else {
          EXPECT_GE(level, -1e-12);
        }
      }
    }
    EXPECT_NEAR(volume[0], 0.4, 1e-12) << "snap " << snap;
    EXPECT_NEAR(volume[1], 0.6, 1e-12) << "snap " << snap;
    // No part holds tetrahedra of both sides: the sides share no point.
    const std::vector<int> parts = tetrahedron_parts(split.mesh);
    std::map<int, int> side_of_part;
    for (std::size_t t = 0; t < parts.size(); ++t) {
      const auto [it, inserted] = side_of_part.emplace(parts[t], split.side[t]);
      EXPECT_EQ(it->second, split.side[t]);
    }
  }
}

TEST(InterfaceSplit, AMeshThePlaneMissesIsKeptWhole) {
  const TetrahedralMesh cube = test_support::kuhn_cube();
  std::vector<double> level(cube.points.size(), -1.0);
  std::vector<Eigen::Vector3d> normal(cube.points.size(), Eigen::Vector3d::UnitX());
  const InterfaceSplit split = split_at_interface(cube, level, normal);
  EXPECT_EQ(split.mesh.tetrahedra.size(), cube.tetrahedra.size());
  EXPECT_EQ(split.cut_tetrahedra, 0u);
  for (int s : split.side) EXPECT_EQ(s, 0);
  EXPECT_THROW(split_at_interface(cube, std::vector<double>(3, 0.0), normal), InvalidInput);
}

}  // namespace
}  // namespace volspline
