// Vertex clustering for display (mesh/vertex_clustering.h): on a flat grid of two parts the
// clusters are the means of their members, every triangle keeps its orientation and part, the
// budget is met without overshooting it by far, and a mesh within the budget comes back as it was.
#include "volspline/mesh/vertex_clustering.h"

#include <gtest/gtest.h>

#include <set>

#include "volspline/core/error.h"

namespace volspline {
namespace {

// An n x n grid of squares on [0, 1]^2 in the plane z = 0.25 x, two triangles each, counter-
// clockwise seen from above; the left half part 0, the right half part 6.
TriangleMesh clustering_test_grid(int n) {
  TriangleMesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.add_vertex(Eigen::Vector3d(double(i) / n, double(j) / n, 0.25 * i / n), Eigen::Vector3d(i, j, 0));
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      const int part = 2 * i < n ? 0 : 6;
      m.add_triangle(a, b, d, part);
      m.add_triangle(a, d, c, part);
    }
  return m;
}

TEST(VertexClustering, ClustersAreMeansAndTrianglesKeepOrientationAndPart) {
  const TriangleMesh grid = clustering_test_grid(40);
  const ClusteredMesh c = cluster_vertices(grid, 0.1);
  ASSERT_GT(c.mesh.num_triangles(), 0u);
  EXPECT_LT(c.mesh.num_triangles(), grid.num_triangles() / 8);
  // Each cluster is the mean of the vertices mapped to it.
  std::vector<Eigen::Vector3d> sum(c.mesh.num_vertices(), Eigen::Vector3d::Zero());
  std::vector<int> count(c.mesh.num_vertices(), 0);
  for (std::size_t v = 0; v < grid.num_vertices(); ++v) {
    sum[static_cast<std::size_t>(c.cluster_of_vertex[v])] += grid.positions[v];
    ++count[static_cast<std::size_t>(c.cluster_of_vertex[v])];
  }
  for (std::size_t k = 0; k < sum.size(); ++k) {
    EXPECT_LT((sum[k] / count[k] - c.mesh.positions[k]).norm(), 1e-12);
    EXPECT_NEAR(c.mesh.positions[k].z(), 0.25 * c.mesh.positions[k].x(), 1e-12);  // means of points on a plane
  }
  std::set<int> parts;
  for (std::size_t t = 0; t < c.mesh.num_triangles(); ++t) {
    const auto& tri = c.mesh.triangles[t];
    const Eigen::Vector3d n = (c.mesh.positions[static_cast<std::size_t>(tri[1])] - c.mesh.positions[static_cast<std::size_t>(tri[0])])
                                  .cross(c.mesh.positions[static_cast<std::size_t>(tri[2])] - c.mesh.positions[static_cast<std::size_t>(tri[0])]);
    EXPECT_GT(n.z(), 0) << t;  // still counter-clockwise from above
    parts.insert(c.mesh.parts[t]);
  }
  EXPECT_EQ(parts, (std::set<int>{0, 6}));
  EXPECT_THROW(cluster_vertices(grid, 0), InvalidInput);
}

TEST(VertexClustering, MeetsTheBudgetAndLeavesSmallMeshesAlone) {
  const TriangleMesh grid = clustering_test_grid(60);  // 7200 triangles
  const ClusteredMesh reduced = reduce_to_triangle_budget(grid, 1000);
  EXPECT_LE(reduced.mesh.num_triangles(), 1000u);
  EXPECT_GE(reduced.mesh.num_triangles(), 250u);  // one step of 1.25 in cube size changes the count by about 1.6
  EXPECT_GT(reduced.cell_size, 0);
  const ClusteredMesh same = reduce_to_triangle_budget(grid, 7200);
  EXPECT_EQ(same.cell_size, 0);
  EXPECT_EQ(same.mesh.triangles, grid.triangles);
  EXPECT_EQ(same.cluster_of_vertex[17], 17);
  EXPECT_THROW(reduce_to_triangle_budget(grid, 0), InvalidInput);
}

}  // namespace
}  // namespace volspline
