#include "volspline/extract/superset_trimming.h"

#include "clamped_barycentric.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <sstream>

#include <Eigen/Geometry>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Projection_traits_xy_3.h>
#include <CGAL/Projection_traits_xz_3.h>
#include <CGAL/Projection_traits_yz_3.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>
#include <tbb/parallel_for.h>

#include "volspline/core/elapsed_time.h"
#include "volspline/core/error.h"
#include "volspline/mesh/mesh_checks.h"

namespace volspline {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
// Exact constructions: the points where three sheets meet must come out identical from each
// pair's intersection, or the cut pieces would not share their corners.
using Exact = CGAL::Exact_predicates_exact_constructions_kernel;
using ExactPoint = Exact::Point_3;

using Clock = std::chrono::steady_clock;

// The soup cut along all mutual intersections of its triangles: every face lies in one input
// triangle (`origin`), faces meet only along shared edges and at shared corners, and the edges
// along which another triangle cut are `cut_edges` (sorted index pairs).
struct RefinedSoup {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::array<int, 3>> faces;
  std::vector<int> origin;
  std::set<std::pair<int, int>> cut_edges;
};

struct ExactLess {
  bool operator()(const ExactPoint& a, const ExactPoint& b) const { return CGAL::compare_xyz(a, b) == CGAL::SMALLER; }
};

// The constraints one triangle receives from the others: points and segments on it.
struct TriangleCuts {
  std::vector<ExactPoint> points;
  std::vector<Exact::Segment_3> segments;
};

// What of a cut matters to one triangle: a point that is not a corner, a segment that does not
// run along a side (of one that does, its ends, which split the side).
void add_cut_point(const Exact::Triangle_3& t, const ExactPoint& p, TriangleCuts& c) {
  if (p != t.vertex(0) && p != t.vertex(1) && p != t.vertex(2)) c.points.push_back(p);
}

void add_cut_segment(const Exact::Triangle_3& t, const ExactPoint& p, const ExactPoint& q, TriangleCuts& c) {
  if (p == q) return add_cut_point(t, p, c);
  for (int i = 0; i < 3; ++i)
    if (CGAL::collinear(t.vertex(i), t.vertex((i + 1) % 3), p) && CGAL::collinear(t.vertex(i), t.vertex((i + 1) % 3), q)) {
      add_cut_point(t, p, c);
      add_cut_point(t, q, c);
      return;
    }
  c.segments.emplace_back(p, q);
}

void add_intersection(const Exact::Triangle_3& a, const Exact::Triangle_3& b, TriangleCuts& ca, TriangleCuts& cb) {
  if (!CGAL::do_intersect(a, b)) return;
  const auto result = CGAL::intersection(a, b);
  if (!result) return;
  auto add_segment = [&](const ExactPoint& p, const ExactPoint& q) {
    add_cut_segment(a, p, q, ca);
    add_cut_segment(b, p, q, cb);
  };
  if (const auto* p = boost::get<ExactPoint>(&*result)) {
    add_cut_point(a, *p, ca);
    add_cut_point(b, *p, cb);
  } else if (const auto* s = boost::get<Exact::Segment_3>(&*result)) {
    add_segment(s->source(), s->target());
  } else if (const auto* t = boost::get<Exact::Triangle_3>(&*result)) {
    for (int i = 0; i < 3; ++i) add_segment(t->vertex(i), t->vertex((i + 1) % 3));
  } else if (const auto* polygon = boost::get<std::vector<ExactPoint>>(&*result)) {
    for (std::size_t i = 0; i < polygon->size(); ++i) add_segment((*polygon)[i], (*polygon)[(i + 1) % polygon->size()]);
  }
}

// Triangulates triangle `t` with its cuts by CGAL's constrained Delaunay triangulation (exact
// intersections of crossing cuts) in the coordinate plane it projects onto best.
template <class Traits>
void triangulate_cut_triangle(const std::array<ExactPoint, 3>& corners, const TriangleCuts& cuts, bool& flip,
                              std::vector<std::array<ExactPoint, 3>>& faces, std::vector<std::array<ExactPoint, 2>>& cut_edges) {
  using CDT = CGAL::Constrained_Delaunay_triangulation_2<Traits, CGAL::Default, CGAL::Exact_intersections_tag>;
  CDT cdt;
  for (int i = 0; i < 3; ++i) cdt.insert_constraint(corners[static_cast<std::size_t>(i)], corners[static_cast<std::size_t>((i + 1) % 3)]);
  for (const auto& p : cuts.points) cdt.insert(p);
  for (const auto& s : cuts.segments) cdt.insert_constraint(s.source(), s.target());
  const auto orientation = Traits().orientation_2_object();
  flip = orientation(corners[0], corners[1], corners[2]) == CGAL::CLOCKWISE;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f)
    faces.push_back({f->vertex(0)->point(), f->vertex(1)->point(), f->vertex(2)->point()});
  auto on_side = [&](const ExactPoint& p, const ExactPoint& q) {
    for (int i = 0; i < 3; ++i) {
      const ExactPoint& a = corners[static_cast<std::size_t>(i)];
      const ExactPoint& b = corners[static_cast<std::size_t>((i + 1) % 3)];
      if (CGAL::collinear(a, b, p) && CGAL::collinear(a, b, q)) return true;
    }
    return false;
  };
  for (auto e = cdt.finite_edges_begin(); e != cdt.finite_edges_end(); ++e) {
    if (!cdt.is_constrained(*e)) continue;
    const ExactPoint& p = e->first->vertex(CDT::cw(e->second))->point();
    const ExactPoint& q = e->first->vertex(CDT::ccw(e->second))->point();
    if (!on_side(p, q)) cut_edges.push_back({p, q});
  }
}

RefinedSoup refine_soup(const std::vector<Eigen::Vector3d>& positions, const std::vector<std::array<int, 3>>& triangles) {
  std::vector<ExactPoint> exact;
  exact.reserve(positions.size());
  for (const auto& p : positions) exact.emplace_back(p.x(), p.y(), p.z());
  std::vector<Exact::Triangle_3> tri;
  tri.reserve(triangles.size());
  for (const auto& t : triangles)
    tri.emplace_back(exact[static_cast<std::size_t>(t[0])], exact[static_cast<std::size_t>(t[1])], exact[static_cast<std::size_t>(t[2])]);
  // Candidate pairs: overlapping bounding boxes (CGAL's box intersection).
  using Box = CGAL::Box_intersection_d::Box_with_handle_d<double, 3, const Exact::Triangle_3*>;
  std::vector<Box> boxes;
  boxes.reserve(tri.size());
  for (std::size_t i = 0; i < tri.size(); ++i) {
    const auto& p0 = positions[static_cast<std::size_t>(triangles[i][0])];
    CGAL::Bbox_3 b(p0.x(), p0.y(), p0.z(), p0.x(), p0.y(), p0.z());
    for (int j = 1; j < 3; ++j) {
      const auto& p = positions[static_cast<std::size_t>(triangles[i][static_cast<std::size_t>(j)])];
      b += CGAL::Bbox_3(p.x(), p.y(), p.z(), p.x(), p.y(), p.z());
    }
    boxes.emplace_back(b, &tri[i]);
  }
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& a, const Box& b) {
    const auto i = static_cast<std::size_t>(a.handle() - tri.data()), j = static_cast<std::size_t>(b.handle() - tri.data());
    pairs.emplace_back(std::min(i, j), std::max(i, j));
  });
  std::sort(pairs.begin(), pairs.end());
  std::vector<TriangleCuts> cuts(tri.size());
  for (const auto& [i, j] : pairs) {
    // Two triangles sharing an edge and not coplanar meet in that edge only.
    int shared = 0;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) shared += triangles[i][static_cast<std::size_t>(a)] == triangles[j][static_cast<std::size_t>(b)];
    // Two triangles sharing an edge meet in that edge only, unless they are coplanar and on
    // the same side of it (a fold).
    if (shared >= 2) {
      const auto& ti = triangles[i];
      const auto& tj = triangles[j];
      int other_j = -1, other_i = -1;
      std::array<int, 2> edge{};
      int k = 0;
      for (int b = 0; b < 3; ++b) {
        const int vj = tj[static_cast<std::size_t>(b)];
        if (std::find(ti.begin(), ti.end(), vj) == ti.end()) other_j = vj;
        else if (k < 2) edge[static_cast<std::size_t>(k++)] = vj;
      }
      for (int a = 0; a < 3; ++a)
        if (std::find(tj.begin(), tj.end(), ti[static_cast<std::size_t>(a)]) == tj.end()) other_i = ti[static_cast<std::size_t>(a)];
      if (other_i < 0 || other_j < 0) continue;  // the same triangle twice
      const ExactPoint &e0 = exact[static_cast<std::size_t>(edge[0])], &e1 = exact[static_cast<std::size_t>(edge[1])];
      const ExactPoint &oi = exact[static_cast<std::size_t>(other_i)], &oj = exact[static_cast<std::size_t>(other_j)];
      if (!CGAL::coplanar(e0, e1, oi, oj) || CGAL::coplanar_orientation(e0, e1, oi, oj) == CGAL::NEGATIVE) continue;
    }
    // Sharing one corner, they meet only there when the other's two free corners lie strictly
    // on one side of either's plane: decided by predicates alone, which matters because the
    // constructions at a shared corner are degenerate and so evaluated exactly (slowly).
    if (shared == 1) {
      auto one_side = [&](std::size_t p, std::size_t q) {
        std::array<CGAL::Orientation, 2> o{};
        int k = 0;
        for (int b = 0; b < 3; ++b) {
          const int vq = triangles[q][static_cast<std::size_t>(b)];
          if (std::find(triangles[p].begin(), triangles[p].end(), vq) != triangles[p].end()) continue;
          o[static_cast<std::size_t>(k++)] = CGAL::orientation(tri[p].vertex(0), tri[p].vertex(1), tri[p].vertex(2), exact[static_cast<std::size_t>(vq)]);
        }
        return o[0] != CGAL::COPLANAR && o[0] == o[1];
      };
      if (one_side(i, j) || one_side(j, i)) continue;
    }
    add_intersection(tri[i], tri[j], cuts[i], cuts[j]);
  }
  RefinedSoup out;
  std::map<ExactPoint, int, ExactLess> index;
  auto id = [&](const ExactPoint& p) {
    const auto [it, fresh] = index.try_emplace(p, static_cast<int>(out.points.size()));
    if (fresh) out.points.emplace_back(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
    return it->second;
  };
  for (std::size_t i = 0; i < tri.size(); ++i) {
    const auto& t = triangles[i];
    if (cuts[i].points.empty() && cuts[i].segments.empty()) {
      out.faces.push_back({id(exact[static_cast<std::size_t>(t[0])]), id(exact[static_cast<std::size_t>(t[1])]), id(exact[static_cast<std::size_t>(t[2])])});
      out.origin.push_back(static_cast<int>(i));
      continue;
    }
    const std::array<ExactPoint, 3> corners{exact[static_cast<std::size_t>(t[0])], exact[static_cast<std::size_t>(t[1])], exact[static_cast<std::size_t>(t[2])]};
    const Eigen::Vector3d n = (positions[static_cast<std::size_t>(t[1])] - positions[static_cast<std::size_t>(t[0])])
                                  .cross(positions[static_cast<std::size_t>(t[2])] - positions[static_cast<std::size_t>(t[0])])
                                  .cwiseAbs();
    std::vector<std::array<ExactPoint, 3>> faces;
    std::vector<std::array<ExactPoint, 2>> cut_edges;
    bool flip = false;
    if (n.z() >= n.x() && n.z() >= n.y()) triangulate_cut_triangle<CGAL::Projection_traits_xy_3<Exact>>(corners, cuts[i], flip, faces, cut_edges);
    else if (n.y() >= n.x()) triangulate_cut_triangle<CGAL::Projection_traits_xz_3<Exact>>(corners, cuts[i], flip, faces, cut_edges);
    else triangulate_cut_triangle<CGAL::Projection_traits_yz_3<Exact>>(corners, cuts[i], flip, faces, cut_edges);
    for (const auto& f : faces) {
      std::array<int, 3> v{id(f[0]), id(f[1]), id(f[2])};
      if (flip) std::swap(v[1], v[2]);
      out.faces.push_back(v);
      out.origin.push_back(static_cast<int>(i));
    }
    for (const auto& e : cut_edges) {
      const int a = id(e[0]), b = id(e[1]);
      out.cut_edges.emplace(std::min(a, b), std::max(a, b));
    }
  }
  return out;
}


// Barycentric coordinates of p with respect to triangle (a, b, c), from the projection of p on
// its plane; clamped to the triangle (p lies on it up to rounding).

enum class Verdict { KeepAsIs, Flip, Inside, Outside, Undecided };

}  // namespace

void measure_trimmed_boundary(const TriangleMesh& mesh, SupersetTrimmingStats& stats,
                              std::vector<std::pair<std::size_t, std::size_t>>* intersecting_faces, SelfIntersectionRecord* record) {
  validate_mesh(mesh);
  stats.result_triangles = static_cast<std::int64_t>(mesh.num_triangles());
  const EdgeStatistics edges = edge_statistics(mesh);
  stats.closed = edges.closed();
  stats.oriented = edges.closed_and_oriented();
  stats.boundary_edges = static_cast<std::int64_t>(edges.boundary_edges);
  stats.nonmanifold_edges = static_cast<std::int64_t>(edges.nonmanifold_edges);
  stats.volume = enclosed_volume(mesh);
  if (stats.boundary_edges > 0) {
    std::map<std::pair<int, int>, int> count;
    for (const auto& t : mesh.triangles)
      for (int j = 0; j < 3; ++j) {
        const int a = t[static_cast<std::size_t>(j)], b = t[static_cast<std::size_t>((j + 1) % 3)];
        ++count[{std::min(a, b), std::max(a, b)}];
      }
    std::ostringstream where;
    int shown = 0;
    for (const auto& [e, n] : count) {
      if (n != 1) continue;
      const Eigen::Vector3d m = 0.5 * (mesh.positions[static_cast<std::size_t>(e.first)] + mesh.positions[static_cast<std::size_t>(e.second)]);
      where << (shown ? "; " : "") << m.x() << " " << m.y() << " " << m.z();
      if (++shown == 4) break;
    }
    stats.open_at = where.str();
  }
  // Connected components by shared vertices.
  {
    std::vector<int> parent(mesh.num_vertices());
    std::iota(parent.begin(), parent.end(), 0);
    auto find = [&](int a) {
      while (parent[static_cast<std::size_t>(a)] != a) a = parent[static_cast<std::size_t>(a)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(a)])];
      return a;
    };
    for (const auto& t : mesh.triangles)
      for (int j = 1; j < 3; ++j) parent[static_cast<std::size_t>(find(t[static_cast<std::size_t>(j)]))] = find(t[0]);
    std::vector<bool> root(mesh.num_vertices(), false);
    for (const auto& t : mesh.triangles) root[static_cast<std::size_t>(find(t[0]))] = true;
    stats.components = static_cast<int>(std::count(root.begin(), root.end(), true));
  }
  // Self-intersections of the result as written (doubles), by CGAL's exact predicates.
  const auto pairs = self_intersecting_triangles(mesh, record);
  stats.self_intersecting_pairs = static_cast<std::int64_t>(pairs.size());
  stats.self_intersection_free = pairs.empty();
  if (intersecting_faces) intersecting_faces->insert(intersecting_faces->end(), pairs.begin(), pairs.end());
}

TrimmedBoundary trim_superset(const TriangleMesh& superset, const std::vector<double>& extra,
                              const SupersetSurfacePoint& surface_point, const ImageMembershipTest& inside,
                              const SupersetTrimmingOptions& options) {
  validate_mesh(superset);
  if (!extra.empty() && extra.size() != superset.num_vertices())
    throw InvalidInput("expected one extra parameter per vertex (" + std::to_string(superset.num_vertices()) + "), got " +
                           std::to_string(extra.size()),
                       "extra");
  if (!(options.offset > 0 && options.offset < 0.1)) throw InvalidInput("expected 0 < offset < 0.1", "offset");
  if (!(options.duplicate_distance >= 0 && options.duplicate_distance < 0.1))
    throw InvalidInput("expected 0 <= duplicate_distance < 0.1", "duplicate_distance");
  if (options.samples_per_piece < 1) throw InvalidInput("expected at least one sample per piece", "samples_per_piece");
  TrimmedBoundary out;
  SupersetTrimmingStats& stats = out.stats;
  stats.superset_triangles = static_cast<std::int64_t>(superset.num_triangles());
  if (superset.num_triangles() == 0) return out;
  const auto [lo, hi] = superset.bounding_box();
  const double diagonal = std::max((hi - lo).norm(), 1e-300);
  const double offset = options.offset * diagonal;

  // The soup: exactly coincident positions are one point; degenerate triangles go.
  const auto refine_start = Clock::now();
  if (options.progress) options.progress->begin_phase("refinement");
  std::vector<Eigen::Vector3d> points;
  std::vector<int> point_of_vertex(superset.num_vertices());
  {
    std::map<std::array<double, 3>, int> index;
    for (std::size_t v = 0; v < superset.num_vertices(); ++v) {
      const Eigen::Vector3d& p = superset.positions[v];
      const auto [it, fresh] = index.try_emplace({p.x(), p.y(), p.z()}, static_cast<int>(points.size()));
      if (fresh) points.push_back(p);
      point_of_vertex[v] = it->second;
    }
  }
  std::vector<std::array<int, 3>> soup;
  std::vector<int> soup_origin;
  const double min_area2 = std::pow(1e-12 * diagonal, 4);
  for (std::size_t f = 0; f < superset.num_triangles(); ++f) {
    const auto& t = superset.triangles[f];
    const std::array<int, 3> p{point_of_vertex[static_cast<std::size_t>(t[0])], point_of_vertex[static_cast<std::size_t>(t[1])],
                               point_of_vertex[static_cast<std::size_t>(t[2])]};
    if (p[0] == p[1] || p[1] == p[2] || p[0] == p[2]) continue;
    const Eigen::Vector3d n = (points[static_cast<std::size_t>(p[1])] - points[static_cast<std::size_t>(p[0])])
                                  .cross(points[static_cast<std::size_t>(p[2])] - points[static_cast<std::size_t>(p[0])]);
    if (n.squaredNorm() <= min_area2) continue;
    soup.push_back(p);
    soup_origin.push_back(static_cast<int>(f));
  }
  RefinedSoup refined = refine_soup(points, soup);
  for (int& o : refined.origin) o = soup_origin[static_cast<std::size_t>(o)];
  const auto& rp = refined.points;
  const auto& rf = refined.faces;
  stats.refined_triangles = static_cast<std::int64_t>(rf.size());
  stats.seconds_refine = seconds_since(refine_start);

  // Pieces: faces of one part connected across edges that exactly two faces share and no
  // other triangle cut; within a piece the faces are made to agree about orientation.
  const auto classify_start = Clock::now();
  if (options.progress) options.progress->begin_phase("classification");
  std::map<std::pair<int, int>, std::vector<int>> edge_faces;
  for (std::size_t f = 0; f < rf.size(); ++f)
    for (int j = 0; j < 3; ++j) {
      const int a = rf[f][static_cast<std::size_t>(j)], b = rf[f][static_cast<std::size_t>((j + 1) % 3)];
      edge_faces[{std::min(a, b), std::max(a, b)}].push_back(static_cast<int>(f));
    }
  auto part_of = [&](std::size_t f) { return superset.parts[static_cast<std::size_t>(refined.origin[f])]; };
  auto traverses = [&](std::size_t f, int a, int b) {
    for (int j = 0; j < 3; ++j)
      if (rf[f][static_cast<std::size_t>(j)] == a && rf[f][static_cast<std::size_t>((j + 1) % 3)] == b) return true;
    return false;
  };
  std::vector<int> piece(rf.size(), -1);
  std::vector<bool> flipped(rf.size(), false);
  std::vector<std::vector<int>> pieces;
  for (std::size_t seed = 0; seed < rf.size(); ++seed) {
    if (piece[seed] >= 0) continue;
    const int id = static_cast<int>(pieces.size());
    pieces.emplace_back();
    std::vector<int> stack{static_cast<int>(seed)};
    piece[seed] = id;
    while (!stack.empty()) {
      const auto f = static_cast<std::size_t>(stack.back());
      stack.pop_back();
      pieces.back().push_back(static_cast<int>(f));
      for (int j = 0; j < 3; ++j) {
        const int a = rf[f][static_cast<std::size_t>(j)], b = rf[f][static_cast<std::size_t>((j + 1) % 3)];
        const std::pair<int, int> e{std::min(a, b), std::max(a, b)};
        if (refined.cut_edges.count(e)) continue;
        const auto& around = edge_faces[e];
        if (around.size() != 2) continue;
        const auto g = static_cast<std::size_t>(around[0] == static_cast<int>(f) ? around[1] : around[0]);
        if (piece[g] >= 0 || part_of(g) != part_of(f)) continue;
        piece[g] = id;
        // f, as oriented now, traverses a -> b (or b -> a if flipped); g agrees if it traverses
        // the edge the other way.
        const bool f_forward = traverses(f, a, b) != flipped[f];
        flipped[g] = traverses(g, a, b) == f_forward;
        stack.push_back(static_cast<int>(g));
      }
    }
  }
  stats.pieces = static_cast<std::int64_t>(pieces.size());

  auto corners = [&](std::size_t f) {
    std::array<Eigen::Vector3d, 3> c{rp[static_cast<std::size_t>(rf[f][0])], rp[static_cast<std::size_t>(rf[f][1])], rp[static_cast<std::size_t>(rf[f][2])]};
    if (flipped[f]) std::swap(c[1], c[2]);
    return c;
  };
  auto origin_corners = [&](int t) {
    const auto& tri = superset.triangles[static_cast<std::size_t>(t)];
    return std::array<Eigen::Vector3d, 3>{superset.positions[static_cast<std::size_t>(tri[0])], superset.positions[static_cast<std::size_t>(tri[1])],
                                          superset.positions[static_cast<std::size_t>(tri[2])]};
  };
  auto area_normal = [](const std::array<Eigen::Vector3d, 3>& c) { return Eigen::Vector3d((c[1] - c[0]).cross(c[2] - c[0])); };

  std::vector<Verdict> verdicts(pieces.size(), Verdict::Undecided);
  std::vector<double> piece_area(pieces.size(), 0);
  std::atomic<std::int64_t> queries{0};
  tbb::parallel_for(std::size_t{0}, pieces.size(), [&](std::size_t p) {
    std::vector<std::pair<double, int>> by_area;
    for (int f : pieces[p]) {
      const double a = area_normal(corners(static_cast<std::size_t>(f))).norm();
      by_area.emplace_back(a, f);
      piece_area[p] += 0.5 * a;
    }
    const std::size_t n = std::min<std::size_t>(by_area.size(), static_cast<std::size_t>(options.samples_per_piece));
    std::partial_sort(by_area.begin(), by_area.begin() + static_cast<std::ptrdiff_t>(n), by_area.end(),
                      [](const auto& a, const auto& b) { return a.first > b.first; });
    std::array<int, 5> votes{};
    for (std::size_t s = 0; s < n; ++s) {
      const auto f = static_cast<std::size_t>(by_area[s].second);
      const auto c = corners(f);
      const Eigen::Vector3d normal = area_normal(c).normalized();
      const Eigen::Vector3d centroid = (c[0] + c[1] + c[2]) / 3;
      const int t = refined.origin[f];
      const auto oc = origin_corners(t);
      const Eigen::Vector3d x = surface_point(static_cast<std::size_t>(t), clamped_barycentric(centroid, oc[0], oc[1], oc[2]));
      const std::optional<bool> front = inside(x + offset * normal), back = inside(x - offset * normal);
      queries += 2;
      Verdict v = Verdict::Undecided;
      if (front && back) {
        if (!*front && *back) v = Verdict::KeepAsIs;
        else if (*front && !*back) v = Verdict::Flip;
        else if (*front && *back) v = Verdict::Inside;
        else v = Verdict::Outside;
      }
      ++votes[static_cast<std::size_t>(v)];
    }
    // The decided answer most samples give; undecided only if no sample was decided.
    int best = static_cast<int>(Verdict::Undecided);
    for (int v = 0; v < 4; ++v)
      if (votes[static_cast<std::size_t>(v)] > 0 &&
          (best == static_cast<int>(Verdict::Undecided) || votes[static_cast<std::size_t>(v)] > votes[static_cast<std::size_t>(best)]))
        best = v;
    verdicts[p] = static_cast<Verdict>(best);
  });
  stats.membership_queries = queries;
  auto kept_piece = [&](std::size_t p) { return verdicts[p] == Verdict::KeepAsIs || verdicts[p] == Verdict::Flip; };

  // Sheets covering the same part of the boundary twice: a kept piece whose largest triangle's
  // centroid lies within duplicate_distance of a larger kept piece facing the same way is dropped.
  using Triangle = Kernel::Triangle_3;
  std::vector<Triangle> kept_triangles;
  std::vector<int> kept_piece_of;
  std::vector<Eigen::Vector3d> kept_outward;
  std::vector<int> largest(pieces.size(), -1);
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    if (!kept_piece(p)) continue;
    double best_area = -1;
    for (int f : pieces[p]) {
      const auto c = corners(static_cast<std::size_t>(f));
      Eigen::Vector3d n = area_normal(c);
      if (n.norm() > best_area) best_area = n.norm(), largest[p] = static_cast<int>(kept_triangles.size());
      if (verdicts[p] == Verdict::Flip) n = -n;
      kept_triangles.emplace_back(Point(c[0].x(), c[0].y(), c[0].z()), Point(c[1].x(), c[1].y(), c[1].z()), Point(c[2].x(), c[2].y(), c[2].z()));
      kept_piece_of.push_back(static_cast<int>(p));
      kept_outward.push_back(n.normalized());
    }
  }
  std::vector<bool> duplicate(pieces.size(), false);
  if (options.duplicate_distance > 0 && !kept_triangles.empty()) {
    using TrianglePrimitive = CGAL::AABB_triangle_primitive<Kernel, std::vector<Triangle>::const_iterator>;
    CGAL::AABB_tree<CGAL::AABB_traits<Kernel, TrianglePrimitive>> tree(kept_triangles.cbegin(), kept_triangles.cend());
    const double d = options.duplicate_distance * diagonal;
    std::vector<int> order;
    for (std::size_t p = 0; p < pieces.size(); ++p)
      if (kept_piece(p)) order.push_back(static_cast<int>(p));
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return piece_area[static_cast<std::size_t>(a)] > piece_area[static_cast<std::size_t>(b)]; });
    std::vector<int> rank(pieces.size(), -1);
    for (std::size_t r = 0; r < order.size(); ++r) rank[static_cast<std::size_t>(order[r])] = static_cast<int>(r);
    for (int p : order) {
      const auto best = static_cast<std::size_t>(largest[static_cast<std::size_t>(p)]);
      const Triangle& t = kept_triangles[best];
      const Point c = CGAL::centroid(t.vertex(0), t.vertex(1), t.vertex(2));
      std::vector<TrianglePrimitive::Id> near;
      const CGAL::Bbox_3 box(c.x() - d, c.y() - d, c.z() - d, c.x() + d, c.y() + d, c.z() + d);
      tree.all_intersected_primitives(box, std::back_inserter(near));
      for (auto id : near) {
        const auto k = static_cast<std::size_t>(id - kept_triangles.cbegin());
        const auto q = static_cast<std::size_t>(kept_piece_of[k]);
        if (static_cast<int>(q) == p || duplicate[q] || rank[q] > rank[static_cast<std::size_t>(p)]) continue;
        if (kept_outward[k].dot(kept_outward[best]) < 0.5) continue;
        if (CGAL::squared_distance(c, kept_triangles[k]) <= d * d) {
          duplicate[static_cast<std::size_t>(p)] = true;
          break;
        }
      }
    }
  }
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    switch (verdicts[p]) {
      case Verdict::KeepAsIs:
      case Verdict::Flip: ++(duplicate[p] ? stats.pieces_duplicate : stats.pieces_boundary); break;
      case Verdict::Inside: ++stats.pieces_inside; break;
      case Verdict::Outside: ++stats.pieces_outside; break;
      case Verdict::Undecided: ++stats.pieces_undecided; break;
    }
  }
  stats.seconds_classify = seconds_since(classify_start);

  // The result, with parameters interpolated in the superset triangle each face was cut from.
  const auto checks_start = Clock::now();
  if (options.progress) options.progress->begin_phase("checks");
  std::vector<int> vertex_out(rp.size(), -1);
  TriangleMesh& result = out.mesh;
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    if (!kept_piece(p) || duplicate[p]) continue;
    for (int fi : pieces[p]) {
      const auto f = static_cast<std::size_t>(fi);
      const int t = refined.origin[f];
      const auto& tri = superset.triangles[static_cast<std::size_t>(t)];
      const auto oc = origin_corners(t);
      std::array<int, 3> ids{};
      for (int k = 0; k < 3; ++k) {
        const auto v = static_cast<std::size_t>(rf[f][static_cast<std::size_t>(k)]);
        int& id = vertex_out[v];
        if (id < 0) {
          const Eigen::Vector3d b = clamped_barycentric(rp[v], oc[0], oc[1], oc[2]);
          Eigen::Vector3d param = Eigen::Vector3d::Zero();
          double e = 0;
          for (int j = 0; j < 3; ++j) {
            param += b[j] * superset.parameters[static_cast<std::size_t>(tri[static_cast<std::size_t>(j)])];
            if (!extra.empty()) e += b[j] * extra[static_cast<std::size_t>(tri[static_cast<std::size_t>(j)])];
          }
          id = result.add_vertex(rp[v], param);
          if (!extra.empty()) out.extra.push_back(e);
          out.source_vertex.push_back(tri[0]);
        }
        ids[static_cast<std::size_t>(k)] = id;
      }
      if (flipped[f] != (verdicts[p] == Verdict::Flip)) std::swap(ids[1], ids[2]);
      result.add_triangle(ids[0], ids[1], ids[2], superset.parts[static_cast<std::size_t>(t)]);
    }
  }
  measure_trimmed_boundary(result, stats);
  stats.seconds_checks = seconds_since(checks_start);
  if (options.progress) options.progress->end_phase();
  return out;
}

}  // namespace volspline
