#pragma once
// A cube domain whose tetrahedra range from small (near the origin) to large (near (1, 1, 1)):
// the Delaunay tetrahedralisation of a grid with coordinates t² (t on a uniform grid), interior
// coordinates slightly jittered so that the tetrahedralisation is unique. For the tests of local
// refinement (mesh/longest_edge_bisection.h, extract/simplex_isosurface.h). Also a cube with a
// cluster of small tetrahedra in one corner and large ones elsewhere.
#include <cmath>
#include <random>
#include <vector>

#include "volspline/mesh/delaunay_tetrahedralization.h"

namespace volspline::test_support {

inline TetrahedralMesh graded_cube_domain(int n = 6, unsigned seed = 11) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> offset(-0.1, 0.1);
  std::vector<double> grid;
  for (int i = 0; i < n; ++i) grid.push_back(std::pow(i / double(n - 1), 2));
  std::vector<Eigen::Vector3d> points;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int index[3] = {i, j, k};
        Eigen::Vector3d p;
        for (int a = 0; a < 3; ++a) {
          const int g = index[a];
          p[a] = grid[static_cast<std::size_t>(g)];
          if (g > 0 && g < n - 1) p[a] += offset(rng) * (grid[static_cast<std::size_t>(g + 1)] - grid[static_cast<std::size_t>(g)]);
        }
        points.push_back(p);
      }
  return delaunay_tetrahedralization(points);
}

/// The unit cube with a cluster of small tetrahedra in its corner [0, 0.3]³ (a jittered
/// m x m x m grid there) and nothing else but the cube's other corners: tetrahedra from about
/// 0.06 to 1.7 across, small and large side by side.
inline TetrahedralMesh clustered_cube_domain(int m = 5, unsigned seed = 5) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> offset(-0.15, 0.15);
  std::vector<Eigen::Vector3d> points;
  const double h = 0.3 / (m - 1);
  for (int k = 0; k < m; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) {
        Eigen::Vector3d p(i * h, j * h, k * h);
        for (int a = 0; a < 3; ++a)
          if (p[a] > 0) p[a] += offset(rng) * h;  // the cube's faces x = 0 etc. stay flat
        points.push_back(p);
      }
  for (int c = 1; c < 8; ++c) points.emplace_back(c & 1, (c >> 1) & 1, (c >> 2) & 1);
  return delaunay_tetrahedralization(points);
}

}  // namespace volspline::test_support
