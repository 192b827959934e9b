// Conforming longest-edge bisection: the result is a valid, face-conforming tetrahedralisation of
// the same domain (same volume, each child inside its parent), every edge below the target, and
// only where the input was coarse.
#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>

#include "support/graded_domain.h"
#include "support/tetrahedral_domains.h"
#include "volspline/core/error.h"
#include "volspline/mesh/longest_edge_bisection.h"
#include "volspline/mesh/mesh_checks.h"

namespace volspline {
namespace {

double signed_volume(const TetrahedralMesh& m, const std::array<int, 4>& t) {
  const auto& p = m.points;
  const Eigen::Vector3d a = p[static_cast<std::size_t>(t[0])];
  return (p[static_cast<std::size_t>(t[1])] - a).dot((p[static_cast<std::size_t>(t[2])] - a).cross(p[static_cast<std::size_t>(t[3])] - a)) / 6;
}

double longest_edge(const TetrahedralMesh& m, const std::array<int, 4>& t) {
  double l = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j)
      l = std::max(l, (m.points[static_cast<std::size_t>(t[static_cast<std::size_t>(i)])] - m.points[static_cast<std::size_t>(t[static_cast<std::size_t>(j)])]).norm());
  return l;
}

TEST(LongestEdgeBisection, StaysConformingAndRefinesOnlyWhereCoarse) {
  const TetrahedralMesh domain = test_support::graded_cube_domain();
  const double longest = longest_edge_length(domain);
  const double target = 0.1;
  ASSERT_GT(longest, 4 * target);
  const LongestEdgeBisection refined = bisect_longest_edges(domain, {.target_edge = target});
  const TetrahedralMesh& m = refined.mesh;
  EXPECT_NO_THROW(validate_tetrahedral_mesh(m));  // positive, every face shared by at most two, no unused points
  EXPECT_LE(longest_edge_length(m), target);
  EXPECT_NEAR(tetrahedral_mesh_volume(m), tetrahedral_mesh_volume(domain), 1e-12);
  ASSERT_EQ(refined.parent.size(), m.tetrahedra.size());
  // The children of each parent fill it: their volumes add up to the parent's.
  std::vector<double> filled(domain.tetrahedra.size(), 0.0);
  for (std::size_t t = 0; t < m.tetrahedra.size(); ++t) filled[static_cast<std::size_t>(refined.parent[t])] += signed_volume(m, m.tetrahedra[t]);
  for (std::size_t t = 0; t < domain.tetrahedra.size(); ++t) EXPECT_NEAR(filled[t], signed_volume(domain, domain.tetrahedra[t]), 1e-13);
  // The boundary is still the cube's surface, closed.
  const TriangleMesh boundary = test_support::boundary_surface(m);
  EXPECT_TRUE(edge_statistics(boundary).closed_and_oriented());
  // Tetrahedra whose edges were already short are untouched (the small ones near the origin).
  std::size_t untouched = 0, short_input = 0;
  std::vector<int> children(domain.tetrahedra.size(), 0);
  for (const int p : refined.parent) ++children[static_cast<std::size_t>(p)];
  for (std::size_t t = 0; t < domain.tetrahedra.size(); ++t) {
    if (longest_edge(domain, domain.tetrahedra[t]) <= target) {
      ++short_input;
      untouched += children[t] == 1;
    }
  }
  EXPECT_GT(short_input, 0u);
  EXPECT_EQ(untouched, short_input);
  // Longest-edge bisection keeps shapes bounded: no child far flatter than the input's worst.
  const auto quality = [](const TetrahedralMesh& mesh) {
    double worst = 1;
    for (const auto& t : mesh.tetrahedra) {
      const double l = longest_edge(mesh, t);
      worst = std::min(worst, 6 * std::sqrt(2.0) * signed_volume(mesh, t) / (l * l * l));  // 1 for the regular tetrahedron
    }
    return worst;
  };
  EXPECT_GT(quality(m), 0.1 * quality(domain));
}

TEST(LongestEdgeBisection, RefusesBadTargets) {
  const TetrahedralMesh domain = test_support::kuhn_cube();
  EXPECT_THROW(bisect_longest_edges(domain, {.target_edge = 0}), InvalidInput);
  EXPECT_THROW(bisect_longest_edges(domain, {.target_edge = std::nan("")}), InvalidInput);
  EXPECT_THROW(bisect_longest_edges(domain, {.target_edge = 1e-3, .max_tetrahedra = 1000}), InvalidInput);
  // A target above every edge leaves the mesh as it is.
  const LongestEdgeBisection same = bisect_longest_edges(domain, {.target_edge = 2});
  EXPECT_EQ(same.mesh.tetrahedra, domain.tetrahedra);
  EXPECT_EQ(same.bisections, 0u);
}

}  // namespace
}  // namespace volspline
