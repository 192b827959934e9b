// MarchingTetrahedra::add_tetrahedron_oriented_by_corners: the same triangles as add_tetrahedron
// wherever they have area, and consistent orientation where sample values are exactly 0 (the
// triangles there have zero area and no normal of their own).
#include "volspline/mesh/marching_tetrahedra.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <random>

#include "volspline/mesh/mesh_checks.h"
#include "volspline/mesh/triangle_mesh.h"

namespace volspline {
namespace {

/// A triangle rotated so its smallest index comes first (same cyclic order).
std::array<int, 3> canonical(std::array<int, 3> t) {
  std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
  return t;
}

TEST(MarchingTetrahedraOrientation, AgreesWithTheNormalWhereTrianglesHaveArea) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int compared = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    std::array<MarchingTetrahedra::Sample, 4> t;
    for (int i = 0; i < 4; ++i) t[static_cast<std::size_t>(i)] = {10 + 7 * i - i * i, Eigen::Vector3d(u(rng), u(rng), u(rng)), u(rng)};
    const double volume = (t[1].point - t[0].point).dot((t[2].point - t[0].point).cross(t[3].point - t[0].point));
    if (std::abs(volume) < 1e-3) continue;
    MarchingTetrahedra by_normal, by_corners;
    by_normal.add_tetrahedron(t);
    by_corners.add_tetrahedron_oriented_by_corners(t);
    ASSERT_EQ(by_normal.vertices(), by_corners.vertices());
    ASSERT_EQ(by_normal.triangles().size(), by_corners.triangles().size());
    std::vector<std::array<int, 3>> a, b;
    for (const auto& tri : by_normal.triangles()) a.push_back(canonical(tri));
    for (const auto& tri : by_corners.triangles()) b.push_back(canonical(tri));
    // The quadrilateral may be split along either diagonal: compare its orientation through the
    // directed edges of its boundary instead of the triangles themselves.
    const auto directed = [](const std::vector<std::array<int, 3>>& tris) {
      std::vector<std::pair<int, int>> edges;
      for (const auto& tri : tris)
        for (int k = 0; k < 3; ++k) edges.emplace_back(tri[k], tri[(k + 1) % 3]);
      std::vector<std::pair<int, int>> boundary;
      for (const auto& e : edges)
        if (std::find(edges.begin(), edges.end(), std::pair{e.second, e.first}) == edges.end()) boundary.push_back(e);
      std::sort(boundary.begin(), boundary.end());
      return boundary;
    };
    EXPECT_EQ(directed(a), directed(b));
    compared += !a.empty();
  }
  EXPECT_GT(compared, 500);
}

TEST(MarchingTetrahedraOrientation, ZeroValuesGiveAClosedConsistentlyOrientedSurface) {
  // |x|² − (3/8)² sampled on a grid of spacing 1/8 cut into 6 tetrahedra per cube: the 30 samples
  // with i² + j² + k² = 9 lie exactly on the sphere (value 0), so surface vertices coincide there.
  const int n = 10;
  const double h = 0.125;
  const auto id = [&](int i, int j, int k) { return static_cast<std::int64_t>(i + (n + 1) * (j + (n + 1) * k)); };
  const auto point = [&](int i, int j, int k) -> Eigen::Vector3d { return Eigen::Vector3d(i - n / 2, j - n / 2, k - n / 2) * h; };
  MarchingTetrahedra mt;
  int zeros = 0;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        // Kuhn's 6 tetrahedra: the paths from corner 0 to corner 7 along the axes.
        static constexpr int kAxes[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
        for (const auto& order : kAxes) {
          std::array<MarchingTetrahedra::Sample, 4> t;
          int c[3] = {i, j, k};
          for (int q = 0; q < 4; ++q) {
            if (q > 0) ++c[order[q - 1]];
            const Eigen::Vector3d x = point(c[0], c[1], c[2]);
            t[static_cast<std::size_t>(q)] = {id(c[0], c[1], c[2]), x, x.squaredNorm() - 9.0 / 64.0};
          }
          mt.add_tetrahedron_oriented_by_corners(t);
        }
      }
  TriangleMesh mesh;
  for (const auto& v : mt.vertices()) mesh.add_vertex(v, v);
  for (const auto& t : mt.triangles()) mesh.add_triangle(t[0], t[1], t[2], 0);
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) zeros += point(i, j, k).squaredNorm() == 9.0 / 64.0;
  EXPECT_EQ(zeros, 30);  // (±3, 0, 0), (±2, ±2, ±1) and their permutations
  const EdgeStatistics e = edge_statistics(mesh);
  EXPECT_TRUE(e.closed_and_oriented()) << e.boundary_edges << " boundary, " << e.inconsistently_oriented_edges << " inconsistent";
  // Outward: the enclosed volume is positive, close to the ball's.
  EXPECT_NEAR(enclosed_volume(mesh), 4.0 / 3.0 * 3.14159265358979 * 0.375 * 0.375 * 0.375, 0.03);
}

}  // namespace
}  // namespace volspline
