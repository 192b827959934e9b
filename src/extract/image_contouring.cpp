#include "volspline/extract/image_contouring.h"

#include "clamped_barycentric.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <map>
#include <unordered_map>
#include <unordered_set>

#include <Eigen/Geometry>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <tbb/parallel_for.h>

#include "volspline/core/elapsed_time.h"
#include "volspline/core/error.h"
#include "volspline/mesh/mesh_checks.h"

namespace volspline {

namespace {

using ContourKernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using ContourPoint = ContourKernel::Point_3;
using ContourTriangle = ContourKernel::Triangle_3;
using ContourPrimitive = CGAL::AABB_triangle_primitive<ContourKernel, std::vector<ContourTriangle>::const_iterator>;
using ContourTree = CGAL::AABB_tree<CGAL::AABB_traits<ContourKernel, ContourPrimitive>>;
using ContourClock = std::chrono::steady_clock;

// Grid points o + h (i, j, k), 0 <= i < n[0] ..., one 64-bit key each; a cell is keyed by its
// lowest corner.
struct ContourGrid {
  Eigen::Vector3d origin;
  double h = 1;
  std::array<std::int64_t, 3> n{};

  std::uint64_t key(std::int64_t i, std::int64_t j, std::int64_t k) const {
    return static_cast<std::uint64_t>((k * n[1] + j) * n[0] + i);
  }
  std::array<std::int64_t, 3> index(std::uint64_t key) const {
    const auto k = static_cast<std::int64_t>(key);
    return {k % n[0], (k / n[0]) % n[1], k / (n[0] * n[1])};
  }
  Eigen::Vector3d point(std::uint64_t key) const {
    const auto i = index(key);
    return origin + h * Eigen::Vector3d(static_cast<double>(i[0]), static_cast<double>(i[1]), static_cast<double>(i[2]));
  }
};

Eigen::Vector3d contour_barycentric(const Eigen::Vector3d& p, const ContourTriangle& t) {
  return clamped_barycentric(p, Eigen::Vector3d(t[0].x(), t[0].y(), t[0].z()), Eigen::Vector3d(t[1].x(), t[1].y(), t[1].z()),
                             Eigen::Vector3d(t[2].x(), t[2].y(), t[2].z()));
}

// Where the boundary crosses one grid edge: the point, and the superset triangle it lies on
// with barycentric coordinates there.
struct ContourCrossing {
  Eigen::Vector3d position;
  std::size_t triangle = 0;
  Eigen::Vector3d barycentric;
  bool on_superset = true;
};

// The six Kuhn tetrahedra of the unit cube: 000 -> e_p0 -> e_p0 + e_p1 -> 111 for each
// permutation p of the axes. Corner c of the cube is bit 0: x, bit 1: y, bit 2: z.
constexpr std::array<std::array<int, 4>, 6> kContourKuhnTetrahedra{{
    {0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7}, {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7},
}};

}  // namespace

TrimmedBoundary contour_image_boundary(const TriangleMesh& superset, const std::vector<double>& extra,
                                       const ImageMembershipTest& inside, const ImageContouringOptions& options) {
  validate_mesh(superset);
  if (!extra.empty() && extra.size() != superset.num_vertices())
    throw InvalidInput("expected one extra parameter per vertex (" + std::to_string(superset.num_vertices()) + "), got " +
                           std::to_string(extra.size()),
                       "extra");
  if (!(options.cell_size > 0 && options.cell_size < 0.5)) throw InvalidInput("expected 0 < cell_size < 0.5", "cell_size");
  if (!(options.superset_error >= 0 && options.superset_error < 0.5))
    throw InvalidInput("expected 0 <= superset_error < 0.5", "superset_error");
  if (options.bisection_steps < 1 || options.bisection_steps > 60) throw InvalidInput("expected 1 to 60 bisection steps", "bisection_steps");
  if (options.max_cells < 1) throw InvalidInput("expected a positive budget of cells", "max_cells");
  TrimmedBoundary out;
  SupersetTrimmingStats& stats = out.stats;
  stats.superset_triangles = static_cast<std::int64_t>(superset.num_triangles());
  if (superset.num_triangles() == 0) return out;

  const auto grid_start = ContourClock::now();
  if (options.progress) options.progress->begin_phase("contouring grid");
  const auto [lo, hi] = superset.bounding_box();
  const double diagonal = std::max((hi - lo).norm(), 1e-300);
  ContourGrid grid;
  grid.h = options.cell_size * diagonal;
  grid.origin = lo - Eigen::Vector3d::Constant(2 * grid.h);
  for (int d = 0; d < 3; ++d) grid.n[static_cast<std::size_t>(d)] = static_cast<std::int64_t>(std::ceil((hi[d] - lo[d]) / grid.h)) + 5;
  stats.cell_size = grid.h;
  const double reach = options.superset_error * diagonal;

  std::vector<ContourTriangle> triangles;
  triangles.reserve(superset.num_triangles());
  for (const auto& t : superset.triangles) {
    std::array<ContourPoint, 3> c;
    for (int j = 0; j < 3; ++j) {
      const Eigen::Vector3d& p = superset.positions[static_cast<std::size_t>(t[static_cast<std::size_t>(j)])];
      c[static_cast<std::size_t>(j)] = ContourPoint(p.x(), p.y(), p.z());
    }
    triangles.emplace_back(c[0], c[1], c[2]);
  }

  // The cells within `reach` of a superset triangle (closed boxes: a point on a cell face
  // counts for both cells).
  std::vector<std::uint64_t> cell_list;
  for (const ContourTriangle& t : triangles) {
    const CGAL::Bbox_3 b = t.bbox();
    std::array<std::int64_t, 3> first{}, last{};
    for (int d = 0; d < 3; ++d) {
      const auto du = static_cast<std::size_t>(d);
      first[du] = std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((b.min(d) - reach - grid.origin[d]) / grid.h)) - 1, 0, grid.n[du] - 2);
      last[du] = std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((b.max(d) + reach - grid.origin[d]) / grid.h)), 0, grid.n[du] - 2);
    }
    const bool small = last[0] - first[0] <= 2 && last[1] - first[1] <= 2 && last[2] - first[2] <= 2;
    for (std::int64_t k = first[2]; k <= last[2]; ++k)
      for (std::int64_t j = first[1]; j <= last[1]; ++j)
        for (std::int64_t i = first[0]; i <= last[0]; ++i) {
          if (!small) {
            const Eigen::Vector3d c = grid.origin + grid.h * Eigen::Vector3d(static_cast<double>(i), static_cast<double>(j), static_cast<double>(k));
            const double m = reach + 1e-9 * grid.h;
            if (!CGAL::do_intersect(t, CGAL::Bbox_3(c.x() - m, c.y() - m, c.z() - m, c.x() + grid.h + m, c.y() + grid.h + m, c.z() + grid.h + m)))
              continue;
          }
          cell_list.push_back(grid.key(i, j, k));
        }
    if (static_cast<std::int64_t>(cell_list.size()) > 4 * options.max_cells) {
      std::sort(cell_list.begin(), cell_list.end());
      cell_list.erase(std::unique(cell_list.begin(), cell_list.end()), cell_list.end());
    }
    if (static_cast<std::int64_t>(cell_list.size()) > options.max_cells)
      throw InvalidInput("the contouring grid needs more than " + std::to_string(options.max_cells) + " cells; choose a larger cell size",
                         "cell_size");
  }
  std::unordered_set<std::uint64_t> cells(cell_list.begin(), cell_list.end());
  cell_list.clear();
  stats.seconds_refine = seconds_since(grid_start);

  // Classification of corners, growing the region across faces whose corners disagree.
  const auto classify_start = ContourClock::now();
  if (options.progress) options.progress->begin_phase("contouring classification");
  std::unordered_map<std::uint64_t, char> label;
  std::atomic<std::int64_t> queries{0};
  auto is_inside = [&](const Eigen::Vector3d& x) {
    ++queries;
    const std::optional<bool> answer = inside(x);
    return !answer || *answer;
  };
  auto corner_key = [&](std::uint64_t cell, int c) {
    const auto i = grid.index(cell);
    return grid.key(i[0] + (c & 1), i[1] + ((c >> 1) & 1), i[2] + ((c >> 2) & 1));
  };
  std::vector<std::uint64_t> frontier(cells.begin(), cells.end());
  while (!frontier.empty()) {
    std::vector<std::uint64_t> fresh;
    for (std::uint64_t cell : frontier)
      for (int c = 0; c < 8; ++c) {
        const std::uint64_t k = corner_key(cell, c);
        if (label.try_emplace(k, 0).second) fresh.push_back(k);
      }
    std::vector<char> values(fresh.size());
    tbb::parallel_for(std::size_t{0}, fresh.size(), [&](std::size_t q) { values[q] = is_inside(grid.point(fresh[q])) ? 1 : 0; });
    for (std::size_t q = 0; q < fresh.size(); ++q) label[fresh[q]] = values[q];
    std::vector<std::uint64_t> grown;
    for (std::uint64_t cell : frontier) {
      const auto i = grid.index(cell);
      for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side) {
          std::array<std::int64_t, 3> j = i;
          j[static_cast<std::size_t>(axis)] += side ? 1 : -1;
          if (j[static_cast<std::size_t>(axis)] < 0 || j[static_cast<std::size_t>(axis)] > grid.n[static_cast<std::size_t>(axis)] - 2) continue;
          const std::uint64_t neighbour = grid.key(j[0], j[1], j[2]);
          if (cells.count(neighbour)) continue;
          int in = 0;
          for (int c = 0; c < 8; ++c)
            if (((c >> axis) & 1) == side) in += label.at(corner_key(cell, c));
          if (in == 0 || in == 4) continue;
          cells.insert(neighbour);
          grown.push_back(neighbour);
        }
    }
    if (static_cast<std::int64_t>(cells.size()) > options.max_cells)
      throw InvalidInput("the contouring grid needs more than " + std::to_string(options.max_cells) + " cells; choose a larger cell size",
                         "cell_size");
    frontier = std::move(grown);
  }
  stats.grid_cells = static_cast<std::int64_t>(cells.size());
  stats.grid_corners = static_cast<std::int64_t>(label.size());

  // Marching tetrahedra: triangles as triples of crossed grid edges (inside corner, outside
  // corner), oriented from inside to outside on the edges' midpoints (the level set at 1/2 of
  // the linear interpolant of the labels, whose orientation moving the vertices along their
  // edges does not change).
  std::map<std::pair<std::uint64_t, std::uint64_t>, int> edge_vertex;
  std::vector<std::pair<std::uint64_t, std::uint64_t>> edges;
  std::vector<std::array<int, 3>> faces;
  auto edge_id = [&](std::uint64_t a, std::uint64_t b) {
    const auto [it, fresh] = edge_vertex.try_emplace({a, b}, static_cast<int>(edges.size()));
    if (fresh) edges.emplace_back(a, b);
    return it->second;
  };
  std::vector<std::uint64_t> sorted_cells(cells.begin(), cells.end());
  std::sort(sorted_cells.begin(), sorted_cells.end());
  for (std::uint64_t cell : sorted_cells) {
    std::array<std::uint64_t, 8> key{};
    std::array<char, 8> in{};
    for (int c = 0; c < 8; ++c) {
      key[static_cast<std::size_t>(c)] = corner_key(cell, c);
      in[static_cast<std::size_t>(c)] = label.at(key[static_cast<std::size_t>(c)]);
    }
    auto corner = [](int c) { return Eigen::Vector3d(c & 1, (c >> 1) & 1, (c >> 2) & 1); };
    for (const auto& tet : kContourKuhnTetrahedra) {
      std::vector<int> ins, outs;
      for (int c : tet) (in[static_cast<std::size_t>(c)] ? ins : outs).push_back(c);
      if (ins.empty() || outs.empty()) continue;
      Eigen::Vector3d in_centre = Eigen::Vector3d::Zero(), out_centre = Eigen::Vector3d::Zero();
      for (int c : ins) in_centre += corner(c) / static_cast<double>(ins.size());
      for (int c : outs) out_centre += corner(c) / static_cast<double>(outs.size());
      const Eigen::Vector3d outward = out_centre - in_centre;
      auto emit = [&](std::array<std::pair<int, int>, 3> e) {
        auto mid = [&](const std::pair<int, int>& p) { return Eigen::Vector3d(0.5 * (corner(p.first) + corner(p.second))); };
        if ((mid(e[1]) - mid(e[0])).cross(mid(e[2]) - mid(e[0])).dot(outward) < 0) std::swap(e[1], e[2]);
        std::array<int, 3> f{};
        for (int j = 0; j < 3; ++j)
          f[static_cast<std::size_t>(j)] = edge_id(key[static_cast<std::size_t>(e[static_cast<std::size_t>(j)].first)],
                                                   key[static_cast<std::size_t>(e[static_cast<std::size_t>(j)].second)]);
        faces.push_back(f);
      };
      if (ins.size() == 1) {
        emit({{{ins[0], outs[0]}, {ins[0], outs[1]}, {ins[0], outs[2]}}});
      } else if (outs.size() == 1) {
        emit({{{ins[0], outs[0]}, {ins[1], outs[0]}, {ins[2], outs[0]}}});
      } else {
        // The quadrilateral ac, ad, bd, bc (a, b inside; c, d outside), split along ac-bd.
        const int a = ins[0], b = ins[1], c = outs[0], d = outs[1];
        emit({{{a, c}, {a, d}, {b, d}}});
        emit({{{a, c}, {b, d}, {b, c}}});
      }
    }
  }

  // The crossings: the superset's intersections with the edge, sorted along it; between the
  // inside end and the outside end, the crossing after the last stretch found inside (binary
  // search over the stretches between crossings). Off the superset: bisection.
  // Zero-area triangles of the superset cannot be crossed (and CGAL's segment-triangle
  // intersection requires a proper triangle): the tree holds the others, mapped back by index.
  std::vector<ContourTriangle> proper_triangles;
  std::vector<std::size_t> proper_source;
  for (std::size_t t = 0; t < triangles.size(); ++t)
    if (!triangles[t].is_degenerate()) {
      proper_triangles.push_back(triangles[t]);
      proper_source.push_back(t);
    }
  if (proper_triangles.empty()) throw InvalidInput("the superset has no triangle of nonzero area", "superset");
  ContourTree tree(proper_triangles.cbegin(), proper_triangles.cend());
  tree.build();
  tree.accelerate_distance_queries();
  std::vector<ContourCrossing> crossings(edges.size());
  std::atomic<std::int64_t> off_superset{0};
  tbb::parallel_for(std::size_t{0}, edges.size(), [&](std::size_t e) {
    const Eigen::Vector3d a = grid.point(edges[e].first), b = grid.point(edges[e].second);
    const Eigen::Vector3d ab = b - a;
    using Hit = ContourTree::Intersection_and_primitive_id<ContourKernel::Segment_3>::Type;
    std::vector<Hit> hits;
    tree.all_intersections(ContourKernel::Segment_3(ContourPoint(a.x(), a.y(), a.z()), ContourPoint(b.x(), b.y(), b.z())), std::back_inserter(hits));
    std::vector<std::pair<double, std::size_t>> along;
    auto add = [&](const ContourPoint& p, std::size_t t) {
      along.emplace_back(std::clamp((Eigen::Vector3d(p.x(), p.y(), p.z()) - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0), t);
    };
    for (const Hit& hit : hits) {
      const std::size_t t = proper_source[static_cast<std::size_t>(hit.second - proper_triangles.cbegin())];
      if (const auto* p = boost::get<ContourPoint>(&hit.first)) add(*p, t);
      else if (const auto* s = boost::get<ContourKernel::Segment_3>(&hit.first)) add(CGAL::midpoint(s->source(), s->target()), t);
    }
    std::sort(along.begin(), along.end());
    // Crossings closer than this are one (coincident sheets).
    const double merge = 1e-6;
    std::vector<std::pair<double, std::size_t>> distinct;
    for (const auto& h : along)
      if (distinct.empty() || h.first - distinct.back().first > merge) distinct.push_back(h);
    ContourCrossing& x = crossings[e];
    double lambda = 0.5;
    if (!distinct.empty()) {
      // Stretch s lies between crossing s - 1 and crossing s; stretch 0 is inside, the last outside.
      std::size_t in_stretch = 0, out_stretch = distinct.size();
      while (out_stretch - in_stretch > 1) {
        const std::size_t mid = (in_stretch + out_stretch) / 2;
        const double probe = 0.5 * (distinct[mid - 1].first + distinct[mid].first);
        (is_inside(a + probe * ab) ? in_stretch : out_stretch) = mid;
      }
      lambda = distinct[in_stretch].first;
      x.triangle = distinct[in_stretch].second;
    } else {
      double l = 0, h = 1;
      for (int s = 0; s < options.bisection_steps; ++s) {
        const double m = 0.5 * (l + h);
        (is_inside(a + m * ab) ? l : h) = m;
      }
      lambda = 0.5 * (l + h);
      const Eigen::Vector3d p = a + lambda * ab;
      const auto closest = tree.closest_point_and_primitive(ContourPoint(p.x(), p.y(), p.z()));
      x.triangle = proper_source[static_cast<std::size_t>(closest.second - proper_triangles.cbegin())];
      x.on_superset = false;
      ++off_superset;
    }
    // Strictly inside the edge, so that no triangle degenerates.
    lambda = std::clamp(lambda, 1e-4, 1 - 1e-4);
    x.position = a + lambda * ab;
    x.barycentric = contour_barycentric(x.position, triangles[x.triangle]);
  });
  stats.membership_queries = queries;
  stats.crossings_off_superset = off_superset;
  stats.seconds_classify = seconds_since(classify_start);

  // The mesh: parameters (and extra) interpolated in the crossing's superset triangle; a face
  // takes the part most of its vertices' triangles have.
  const auto checks_start = ContourClock::now();
  if (options.progress) options.progress->begin_phase("checks");
  TriangleMesh& result = out.mesh;
  std::vector<int> vertex_part(crossings.size());
  for (std::size_t e = 0; e < crossings.size(); ++e) {
    const ContourCrossing& x = crossings[e];
    const auto& tri = superset.triangles[x.triangle];
    Eigen::Vector3d param = Eigen::Vector3d::Zero();
    double value = 0;
    for (int j = 0; j < 3; ++j) {
      const auto v = static_cast<std::size_t>(tri[static_cast<std::size_t>(j)]);
      param += x.barycentric[j] * superset.parameters[v];
      if (!extra.empty()) value += x.barycentric[j] * extra[v];
    }
    result.add_vertex(x.position, param);
    if (!extra.empty()) out.extra.push_back(value);
    out.source_vertex.push_back(tri[0]);
    vertex_part[e] = superset.parts[x.triangle];
  }
  for (const auto& f : faces) {
    const int p0 = vertex_part[static_cast<std::size_t>(f[0])], p1 = vertex_part[static_cast<std::size_t>(f[1])],
              p2 = vertex_part[static_cast<std::size_t>(f[2])];
    result.add_triangle(f[0], f[1], f[2], (p1 == p2 && p1 != p0) ? p1 : p0);
  }
  measure_trimmed_boundary(result, stats);
  stats.seconds_checks = seconds_since(checks_start);
  if (options.progress) options.progress->end_phase();
  return out;
}

}  // namespace volspline
