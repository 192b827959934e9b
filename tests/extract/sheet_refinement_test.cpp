// Refinement toward the sheets (extract/sheet_refinement.h) on an analytic sheet, the unit
// sphere: every vertex stays on it, every edge ends within the tolerance of it at its midpoint,
// the mesh stays closed and consistently oriented, and the enclosed volume converges to 4/3 pi
// from below as an inscribed polyhedron's must.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include "volspline/extract/sheet_refinement.h"
#include "volspline/mesh/mesh_checks.h"

namespace volspline {
namespace {

// The unit sphere as a sheet: parameters are the point itself; the crossing of [a, b] nearest
// the starting lambda.
std::optional<SheetCrossing> sphere_crossing(const Eigen::Vector4d&, double lambda, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d d = b - a;
  const double qa = d.squaredNorm(), qb = 2 * a.dot(d), qc = a.squaredNorm() - 1;
  const double disc = qb * qb - 4 * qa * qc;
  if (disc < 0) return std::nullopt;
  std::optional<double> best;
  for (double s : {-1.0, 1.0}) {
    const double l = (-qb + s * std::sqrt(disc)) / (2 * qa);
    if (l >= 0 && l <= 1 && (!best || std::abs(l - lambda) < std::abs(*best - lambda))) best = l;
  }
  if (!best) return std::nullopt;
  SheetCrossing c;
  c.lambda = *best;
  c.parameters = a + *best * d;
  c.normal = c.parameters.normalized();
  return c;
}

TriangleMesh octahedron(std::vector<SheetVertex>& vertices) {
  TriangleMesh mesh;
  const std::vector<Eigen::Vector3d> p{Eigen::Vector3d::UnitX(), -Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(),
                                       -Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ(), -Eigen::Vector3d::UnitZ()};
  for (const auto& x : p) {
    mesh.add_vertex(x, x);
    SheetVertex v;
    v.on[0].sheet = 0;
    v.on[0].parameters << x, 0;
    v.on[0].normal = x;
    vertices.push_back(v);
  }
  for (int top : {4, 5})
    for (auto [i, j] : {std::pair{0, 2}, {2, 1}, {1, 3}, {3, 0}}) {
      if (top == 4) mesh.add_triangle(i, j, top, 0);
      else mesh.add_triangle(j, i, top, 0);
    }
  return mesh;
}

TEST(SheetRefinement, AnInscribedOctahedronIsRefinedOntoTheSphereToTheTolerance) {
  std::vector<SheetVertex> vertices;
  TriangleMesh mesh = octahedron(vertices);
  ASSERT_GT(enclosed_volume(mesh), 0);
  const SheetCrossingFrom crossing = [](std::size_t, const Eigen::Vector4d& start, double lambda, const Eigen::Vector3d& a,
                                        const Eigen::Vector3d& b) { return sphere_crossing(start, lambda, a, b); };
  std::vector<std::size_t> origin;
  SheetRefinementOptions options;
  options.tolerance = 1e-3;
  const SheetRefinementStats stats = refine_to_sheets(mesh, vertices, crossing, options, &origin);
  EXPECT_EQ(stats.edges_above_tolerance, 0);
  EXPECT_EQ(stats.failed_edges, 0);
  EXPECT_EQ(stats.unresolved_edges, 0);
  EXPECT_GT(stats.rounds, 3);
  ASSERT_EQ(vertices.size(), mesh.num_vertices());
  ASSERT_EQ(origin.size(), mesh.num_triangles());
  EXPECT_TRUE(std::all_of(origin.begin(), origin.end(), [](std::size_t f) { return f < 8; }));
  for (std::size_t v = 0; v < mesh.num_vertices(); ++v) {
    EXPECT_NEAR(mesh.positions[v].norm(), 1, 1e-12);
    EXPECT_NEAR((vertices[v].on[0].normal - mesh.positions[v]).norm(), 0, 1e-12);
  }
  EXPECT_TRUE(stats.unverified_edges.empty());
  const EdgeStatistics edges = edge_statistics(mesh);
  EXPECT_TRUE(edges.closed_and_oriented());
  // Every face faces outward (none turned over while consistent with its neighbours).
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d &a = mesh.positions[static_cast<std::size_t>(t[0])], &b = mesh.positions[static_cast<std::size_t>(t[1])],
                          &c = mesh.positions[static_cast<std::size_t>(t[2])];
    EXPECT_GT((b - a).cross(c - a).dot(a + b + c), 0);
  }
  std::set<std::pair<int, int>> seen;
  double worst = 0;
  for (const auto& t : mesh.triangles)
    for (int j = 0; j < 3; ++j) {
      const int p = t[static_cast<std::size_t>(j)], q = t[static_cast<std::size_t>((j + 1) % 3)];
      if (!seen.emplace(std::min(p, q), std::max(p, q)).second) continue;
      worst = std::max(worst, 1 - (0.5 * (mesh.positions[static_cast<std::size_t>(p)] + mesh.positions[static_cast<std::size_t>(q)])).norm());
    }
  EXPECT_LE(worst, options.tolerance);
  // Inscribed, so below the ball's volume; each triangle's cap is at most 4/3 of its edges'
  // deviation deep.
  const double volume = enclosed_volume(mesh), ball = 4.0 / 3 * std::numbers::pi;
  EXPECT_LT(volume, ball);
  EXPECT_GT(volume, ball - 4 * std::numbers::pi * (4.0 / 3) * options.tolerance);
}

TEST(SheetRefinement, EdgesAcrossTwoSheetsAtACreaseAreCountedNotSplit) {
  // The same octahedron with its lower half on another sheet: the equator's edges to the south
  // pole join two sheets at 90 degrees, which without a membership test is a crease that no
  // crease point resolves.
  std::vector<SheetVertex> vertices;
  TriangleMesh mesh = octahedron(vertices);
  vertices[5].on[0].sheet = 1;
  const SheetCrossingFrom crossing = [](std::size_t, const Eigen::Vector4d& start, double lambda, const Eigen::Vector3d& a,
                                        const Eigen::Vector3d& b) { return sphere_crossing(start, lambda, a, b); };
  SheetRefinementOptions options;
  options.tolerance = 1e-2;
  const SheetRefinementStats stats = refine_to_sheets(mesh, vertices, crossing, options);
  // The four edges at the pole, and those the splits of the equator's edges add there.
  EXPECT_GE(stats.unresolved_edges, 4);
  ASSERT_FALSE(stats.unverified_edges.empty());
  std::set<std::pair<int, int>> edges;
  for (const auto& t : mesh.triangles)
    for (int j = 0; j < 3; ++j)
      edges.emplace(std::min(t[static_cast<std::size_t>(j)], t[static_cast<std::size_t>((j + 1) % 3)]),
                    std::max(t[static_cast<std::size_t>(j)], t[static_cast<std::size_t>((j + 1) % 3)]));
  for (const auto& [p, q] : stats.unverified_edges) {
    EXPECT_TRUE(p == 5 || q == 5) << p << " " << q;
    EXPECT_TRUE(edges.count({std::min(p, q), std::max(p, q)})) << p << " " << q;
  }
  EXPECT_TRUE(edge_statistics(mesh).closed_and_oriented());
  for (const auto& x : mesh.positions) EXPECT_NEAR(x.norm(), 1, 1e-12);
  SheetRefinementOptions bad = options;
  bad.tolerance = 0;
  EXPECT_THROW(refine_to_sheets(mesh, vertices, crossing, bad), InvalidInput);
  std::vector<SheetVertex> too_few(1);
  EXPECT_THROW(refine_to_sheets(mesh, too_few, crossing, options), InvalidInput);
  TriangleMesh broken = mesh;
  broken.triangles[0][0] = static_cast<int>(broken.num_vertices());  // a corner that is no vertex
  std::vector<SheetVertex> copy = vertices;
  EXPECT_THROW(refine_to_sheets(broken, copy, crossing, options), InvalidInput);
  SheetRefinementOptions unchecked = options;
  unchecked.inside = [](const Eigen::Vector3d& x) { return std::optional<bool>(x.norm() < 1); };
  EXPECT_THROW(refine_to_sheets(mesh, copy, crossing, unchecked), InvalidInput);
}

}  // namespace
}  // namespace volspline
