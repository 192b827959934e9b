// Refinement toward the sheets (extract/sheet_refinement.h) on an analytic sheet, the unit
// sphere: every vertex stays on it, every edge ends within the tolerance of it at its midpoint,
// the mesh stays closed and consistently oriented, and the enclosed volume converges to 4/3 pi
// from below as an inscribed polyhedron's must.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <numbers>
#include <optional>
#include <set>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "volspline/extract/sheet_refinement.h"
#include "volspline/core/error.h"
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

// A memory of splits (SheetRefinementMemory) changes nothing but the work: a call with it gives
// exactly the mesh of a call without it; called again on the same mesh it asks the sheet
// nothing; and where an end differs (its source here) the edges at it are solved again, so the
// result is again the one without memory.
TEST(SheetRefinement, AMemoryOfSplitsReusesEqualEdgesOnlyAndChangesNoResult) {
  std::atomic<int> asked{0};
  const SheetCrossingFrom crossing = [&](std::size_t, const Eigen::Vector4d& start, double lambda, const Eigen::Vector3d& a,
                                         const Eigen::Vector3d& b) {
    ++asked;
    return sphere_crossing(start, lambda, a, b);
  };
  const auto refined = [&](SheetRefinementMemory* memory, int source_of_vertex_0) {
    std::vector<SheetVertex> vertices;
    TriangleMesh mesh = octahedron(vertices);
    vertices[0].source = source_of_vertex_0;
    SheetRefinementOptions options;
    options.tolerance = 1e-3;
    options.memory = memory;
    std::vector<std::size_t> origin;
    refine_to_sheets(mesh, vertices, crossing, options, &origin);
    return std::tuple{mesh, vertices, origin};
  };
  const auto same = [](const auto& x, const auto& y) {
    const auto& [mx, vx, ox] = x;
    const auto& [my, vy, oy] = y;
    if (mx.positions != my.positions || mx.triangles != my.triangles || mx.parts != my.parts || ox != oy || vx.size() != vy.size()) return false;
    for (std::size_t v = 0; v < vx.size(); ++v)
      if (vx[v].source != vy[v].source || vx[v].on[0].parameters != vy[v].on[0].parameters || vx[v].on[0].normal != vy[v].on[0].normal)
        return false;
    return true;
  };
  const auto plain = refined(nullptr, 0);
  const int plain_asked = asked.exchange(0);
  ASSERT_GT(plain_asked, 0);
  SheetRefinementMemory memory;
  EXPECT_TRUE(same(refined(&memory, 0), plain));
  EXPECT_EQ(asked.exchange(0), plain_asked);
  EXPECT_EQ(memory.reused(), 0u);
  const std::size_t remembered = memory.size();
  EXPECT_GT(remembered, 0u);
  EXPECT_TRUE(same(refined(&memory, 0), plain));
  EXPECT_EQ(asked.exchange(0), 0);
  EXPECT_EQ(memory.reused(), remembered);
  // Vertex 0 from another source: its edges' splits (which carry the source on) are not reused.
  const auto other = refined(nullptr, 7);
  asked = 0;
  EXPECT_TRUE(same(refined(&memory, 7), other));
  EXPECT_GT(asked.load(), 0);
  EXPECT_LT(asked.load(), plain_asked);
  // A moved-from memory is empty and usable.
  SheetRefinementMemory moved = std::move(memory);
  EXPECT_GT(moved.size(), 0u);
  EXPECT_EQ(memory.size(), 0u);  // NOLINT(bugprone-use-after-move): the documented state
  EXPECT_TRUE(same(refined(&memory, 0), plain));
  EXPECT_GT(memory.size(), 0u);
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

// One sheet with two branches that cross (the boundary of the union of two unit balls centred
// at (-0.8, 0, 0) and (0.8, 0, 0), both spheres one sheet as a face sweep's fold that folds over
// itself is): the parameters are the point and, fourth, the branch (-1 or 1; anything else, a
// mean of the two branches, has no crossing).
std::optional<SheetCrossing> two_ball_crossing(const Eigen::Vector4d& start, double lambda, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  if (std::abs(std::abs(start[3]) - 1) > 1e-12) return std::nullopt;
  const Eigen::Vector3d centre(0.8 * start[3], 0, 0);
  std::optional<SheetCrossing> c = sphere_crossing(start, lambda, a - centre, b - centre);
  if (!c) return c;
  c->parameters += centre;
  c->extra = start[3];
  return c;
}

TEST(SheetRefinement, TwoBranchesOfOneSheetAreToldApartByTheirNormals) {
  // A coarse mesh of the union's boundary: 16 vertices on the circle where the spheres cross
  // (x = 0, radius 0.6; the branches' normals there 74 degrees apart), on each sphere rings
  // every 13 degrees of latitude from there to its far pole (x = -1.8 or 1.8), so that
  // neighbours on one branch have normals at most about 26 degrees apart (across a diagonal).
  const auto make = [](std::vector<SheetVertex>& vertices, bool crease_on_both) {
    TriangleMesh mesh;
    vertices.clear();
    auto point_on = [](int branch, const Eigen::Vector3d& x) {
      SheetPoint p;
      p.sheet = 0;
      p.parameters << x, branch;
      p.normal = x - Eigen::Vector3d(0.8 * branch, 0, 0);
      return p;
    };
    const int longitudes = 16, rings = 10;
    const double crease_angle = std::acos(0.8);
    auto add = [&](const Eigen::Vector3d& x, int branch, bool crease) {
      mesh.add_vertex(x, x);
      SheetVertex v;
      v.on[0] = point_on(crease ? -1 : branch, x);
      if (crease && crease_on_both) v.on[1] = point_on(1, x);
      vertices.push_back(v);
      return static_cast<int>(mesh.num_vertices()) - 1;
    };
    std::vector<int> crease;
    for (int k = 0; k < longitudes; ++k) {
      const double around = 2 * std::numbers::pi * k / longitudes;
      crease.push_back(add(Eigen::Vector3d(0, 0.6 * std::cos(around), 0.6 * std::sin(around)), 0, true));
    }
    for (int branch : {-1, 1}) {
      std::vector<int> previous = crease;
      for (int r = 1; r <= rings + 1; ++r) {
        const double phi = crease_angle + r * (std::numbers::pi - crease_angle) / (rings + 1);
        std::vector<int> ring;
        if (r == rings + 1) {
          const int pole = add(Eigen::Vector3d(1.8 * branch, 0, 0), branch, false);
          ring.assign(static_cast<std::size_t>(longitudes), pole);
        } else {
          for (int k = 0; k < longitudes; ++k) {
            const double around = 2 * std::numbers::pi * k / longitudes;
            ring.push_back(add(Eigen::Vector3d(0.8 * branch - branch * std::cos(phi), std::sin(phi) * std::cos(around), std::sin(phi) * std::sin(around)),
                               branch, false));
          }
        }
        for (int k = 0; k < longitudes; ++k) {
          const auto i = static_cast<std::size_t>(k), j = static_cast<std::size_t>((k + 1) % longitudes);
          std::array<int, 3> first{previous[i], previous[j], ring[j]}, second{previous[i], ring[j], ring[i]};
          if (branch < 0) std::swap(first[1], first[2]), std::swap(second[1], second[2]);
          mesh.add_triangle(first[0], first[1], first[2], 14);
          if (r <= rings) mesh.add_triangle(second[0], second[1], second[2], 14);
        }
        previous = ring;
      }
    }
    return mesh;
  };
  const SheetCrossingFrom crossing = [](std::size_t, const Eigen::Vector4d& start, double lambda, const Eigen::Vector3d& a,
                                        const Eigen::Vector3d& b) { return two_ball_crossing(start, lambda, a, b); };
  const auto on_union_boundary = [](const Eigen::Vector3d& x) {
    const double a = (x - Eigen::Vector3d(-0.8, 0, 0)).norm(), b = (x - Eigen::Vector3d(0.8, 0, 0)).norm();
    return std::min(a, b) - 1;  // signed distance to the union's boundary, exact outside, a bound inside
  };
  SheetRefinementOptions options;
  options.tolerance = 2e-3;
  options.branch_angle_degrees = 50;
  std::vector<SheetVertex> vertices;
  TriangleMesh mesh = make(vertices, true);
  ASSERT_GT(enclosed_volume(mesh), 0);
  const SheetRefinementStats stats = refine_to_sheets(mesh, vertices, crossing, options);
  EXPECT_EQ(stats.edges_above_tolerance, 0);
  EXPECT_EQ(stats.failed_edges, 0);
  EXPECT_EQ(stats.unresolved_edges, 0);
  EXPECT_TRUE(edge_statistics(mesh).closed_and_oriented());
  // Every vertex on its own branch (and so on the union's boundary), the crease vertices on both.
  std::size_t crease_vertices = 0;
  for (std::size_t v = 0; v < mesh.num_vertices(); ++v) {
    const Eigen::Vector3d& x = mesh.positions[v];
    EXPECT_NEAR(on_union_boundary(x), 0, 1e-9) << v;
    for (const SheetPoint& p : vertices[v].on) {
      if (p.sheet < 0) continue;
      EXPECT_NEAR((x - Eigen::Vector3d(0.8 * p.parameters[3], 0, 0)).norm(), 1, 1e-9) << v;
    }
    if (vertices[v].on[1].sheet >= 0) {
      ++crease_vertices;
      EXPECT_NEAR(x.x(), 0, 1e-9);
      EXPECT_NE(vertices[v].on[0].parameters[3], vertices[v].on[1].parameters[3]);
    }
  }
  EXPECT_GT(crease_vertices, 16u);  // the crease edges were split along the circle
  // Every edge's midpoint within the tolerance of the boundary (inside it: the chords of convex
  // parts).
  for (const auto& t : mesh.triangles)
    for (int j = 0; j < 3; ++j) {
      const Eigen::Vector3d m =
          0.5 * (mesh.positions[static_cast<std::size_t>(t[static_cast<std::size_t>(j)])] + mesh.positions[static_cast<std::size_t>(t[static_cast<std::size_t>((j + 1) % 3)])]);
      EXPECT_LE(std::abs(on_union_boundary(m)), options.tolerance * 1.0001);
    }
  // With the crease vertices on the first branch alone, the edges from them to the second
  // branch's first ring join two branches: across the crease, not refined, each counted. Taken
  // for one branch (branch angle 0), the sheet is refined along those edges too: Newton from the
  // mean of two branches' parameters finds nothing, and edges stay above the tolerance.
  std::vector<SheetVertex> one_sided;
  TriangleMesh one_sided_mesh = make(one_sided, false);
  std::vector<SheetVertex> one_sided_plain = one_sided;
  TriangleMesh one_sided_plain_mesh = one_sided_mesh;
  const SheetRefinementStats across = refine_to_sheets(one_sided_mesh, one_sided, crossing, options);
  EXPECT_EQ(across.failed_edges, 0);
  EXPECT_EQ(across.edges_above_tolerance, 0);
  EXPECT_GE(across.unresolved_edges, 32);  // two per quadrilateral of the first ring of the second branch
  ASSERT_EQ(across.unverified_edges.size(), static_cast<std::size_t>(across.unresolved_edges));
  for (const auto& [p, q] : across.unverified_edges)
    EXPECT_NE(one_sided[static_cast<std::size_t>(p)].on[0].parameters[3], one_sided[static_cast<std::size_t>(q)].on[0].parameters[3]) << p << " " << q;
  EXPECT_TRUE(edge_statistics(one_sided_mesh).closed_and_oriented());
  SheetRefinementOptions one_branch = options;
  one_branch.branch_angle_degrees = 0;
  const SheetRefinementStats along = refine_to_sheets(one_sided_plain_mesh, one_sided_plain, crossing, one_branch);
  EXPECT_GT(along.failed_edges, 0);
  EXPECT_GT(along.edges_above_tolerance, 0);
  SheetRefinementOptions bad = options;
  bad.branch_angle_degrees = 91;
  EXPECT_THROW(refine_to_sheets(mesh, vertices, crossing, bad), InvalidInput);
}

}  // namespace
}  // namespace volspline
