#include "volspline/extract/image_contouring.h"

#include "clamped_barycentric.h"
#include "triangle_buckets.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>
#include <numeric>
#include <numbers>
#include <optional>
#include <set>
#include <tuple>
#include <unordered_map>
#include <unordered_set>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SVD>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <tbb/concurrent_unordered_map.h>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include "volspline/core/elapsed_time.h"
#include "volspline/core/error.h"
#include "volspline/mesh/marching_tetrahedra.h"
#include "volspline/core/exact_hash.h"
#include "volspline/extract/sheet_refinement.h"
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
// The exact inputs of one sheet_crease_point call (bit patterns), for remembering its answer.
using CreaseKey = std::array<double, 25>;
struct CreaseAnswer {
  std::optional<Eigen::Vector3d> point;
  SheetPoint a, b;
};

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
// With the sheets' equations, the vertex is on the sheet (on_sheet) with its parameters, extra
// parameter and unit normal there.
struct ContourCrossing {
  Eigen::Vector3d position;
  std::size_t triangle = 0;
  Eigen::Vector3d barycentric;
  bool on_sheet = false;
  double lambda = 0;
  Eigen::Vector3d parameters = Eigen::Vector3d::Zero();
  double extra = 0;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  // Placed on a sheet after the bracket was bisected; on no sheet at all.
  bool after_bisection = false;
  bool off_superset = false;
};

// A cell of the contouring complex: its lowest lattice point and its width in lattice steps.
struct ContourCell {
  std::uint64_t low = 0;
  std::int64_t size = 1;
};

// The part of the contour in one tetrahedron: a cycle of 3 or 4 crossings (vertex ids), outward,
// its cell (an index into the complex's cells) and the tetrahedron's lattice points.
struct ContourPolygon {
  std::array<int, 4> vertex{};
  int count = 0;
  std::uint64_t cell = 0;
  std::array<std::uint64_t, 4> tetrahedron{};
};


}  // namespace

TrimmedBoundary contour_image_boundary(const TriangleMesh& superset, const std::vector<double>& extra,
                                       const ImageMembershipTest& inside, const ImageContouringOptions& options,
                                       const SupersetSheetCrossing& sheet_crossing, const std::vector<int>& sheet_of_triangle,
                                       const SheetCrossingFrom& sheet_crossing_from) {
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
  if (options.coarse_ratio < 1 || options.coarse_ratio > 64 || (options.coarse_ratio > 1 && options.coarse_ratio % 2 != 0))
    throw InvalidInput("expected a coarse ratio of 1 or an even number up to 64", "coarse_ratio");
  if (options.crease_width < 1) throw InvalidInput("expected a crease width of at least 1", "crease_width");
  if (!(options.max_adaptation_growth >= 1)) throw InvalidInput("expected an adaptation growth of at least 1", "max_adaptation_growth");
  if (options.max_adaptation_floor < 0) throw InvalidInput("expected a floor of 0 cells or more", "max_adaptation_floor");
  if (!(options.refinement_tolerance >= 0 && options.refinement_tolerance < 0.5))
    throw InvalidInput("expected 0 <= refinement_tolerance < 0.5", "refinement_tolerance");
  if (!(options.verification_distance >= 0 && options.verification_distance < 0.5))
    throw InvalidInput("expected 0 <= verification_distance < 0.5", "verification_distance");
  if (!sheet_of_triangle.empty() && sheet_of_triangle.size() != superset.num_triangles())
    throw InvalidInput("expected one sheet number per triangle (" + std::to_string(superset.num_triangles()) + "), got " +
                           std::to_string(sheet_of_triangle.size()),
                       "sheet_of_triangle");
  TrimmedBoundary out;
  SupersetTrimmingStats& stats = out.stats;
  stats.superset_triangles = static_cast<std::int64_t>(superset.num_triangles());
  if (superset.num_triangles() == 0) return out;

  const auto grid_start = ContourClock::now();
  if (options.progress) options.progress->begin_phase("contouring grid");
  const auto [lo, hi] = superset.bounding_box();
  const double diagonal = std::max((hi - lo).norm(), 1e-300);
  // The lattice of the fine cells; cells are `ratio` lattice steps wide except where they are
  // refined (below).
  const int ratio = options.coarse_ratio;
  ContourGrid grid;
  grid.h = options.cell_size * diagonal;
  const double coarse_h = ratio * grid.h;
  // Shifted by fractions of a cell that no model's round coordinates share, so that planar faces
  // and the creases between them do not run through grid corners and faces (where they would make
  // crossings at the ends of edges and creases on tetrahedron faces).
  grid.origin = lo - coarse_h * Eigen::Vector3d(2.3183, 2.2718, 2.1414);
  std::array<std::int64_t, 3> coarse_n{};
  for (int d = 0; d < 3; ++d) {
    const auto du = static_cast<std::size_t>(d);
    coarse_n[du] = static_cast<std::int64_t>(std::ceil((hi[d] - lo[d]) / coarse_h)) + 5;
    grid.n[du] = ratio * (coarse_n[du] - 1) + 1;
  }
  stats.cell_size = grid.h;
  stats.coarse_ratio = ratio;
  stats.crease_width = options.crease_width;
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

  // The (coarse) cells within `reach` of a superset triangle (closed boxes: a point on a cell face
  // counts for both cells), sorted and distinct. Blocks of triangles are listed in parallel; a
  // block whose listings (with repeats, all threads together) pass the budget stops and is listed
  // again serially, merged whenever its listings pass the budget, so that memory stays within a
  // few times the budget however fine the grid; the budget counts distinct cells.
  std::vector<std::uint64_t> cell_list;
  const auto max_listed = static_cast<std::size_t>(options.max_cells);
  std::atomic<std::size_t> listed_in_block{0};
  std::atomic<bool> block_full{false};
  // Merges sorted-or-not `part` into the sorted, distinct `cell_list`; throws past the budget.
  const auto merge_cells = [&](std::vector<std::uint64_t>& part) {
    tbb::parallel_sort(part.begin(), part.end());
    part.erase(std::unique(part.begin(), part.end()), part.end());
    const auto middle = static_cast<std::ptrdiff_t>(cell_list.size());
    cell_list.insert(cell_list.end(), part.begin(), part.end());
    std::inplace_merge(cell_list.begin(), cell_list.begin() + middle, cell_list.end());
    cell_list.erase(std::unique(cell_list.begin(), cell_list.end()), cell_list.end());
    part.clear();
    if (cell_list.size() > max_listed)
      throw InvalidInput("the contouring grid needs more than " + std::to_string(options.max_cells) + " cells; choose a larger cell size",
                         "cell_size");
  };
  // Lists triangle t's cells into `out`; false if the block filled up (in parallel listing).
  const auto list_cells_of = [&](const ContourTriangle& t, std::vector<std::uint64_t>& out, bool parallel) {
    const CGAL::Bbox_3 b = t.bbox();
    std::array<std::int64_t, 3> first{}, last{};
    for (int d = 0; d < 3; ++d) {
      const auto du = static_cast<std::size_t>(d);
      first[du] = std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((b.min(d) - reach - grid.origin[d]) / coarse_h)) - 1, 0, coarse_n[du] - 2);
      last[du] = std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((b.max(d) + reach - grid.origin[d]) / coarse_h)), 0, coarse_n[du] - 2);
    }
    const bool small = last[0] - first[0] <= 2 && last[1] - first[1] <= 2 && last[2] - first[2] <= 2;
    for (std::int64_t k = first[2]; k <= last[2]; ++k)
      for (std::int64_t j = first[1]; j <= last[1]; ++j) {
        if (parallel && block_full.load(std::memory_order_relaxed)) return false;
        for (std::int64_t i = first[0]; i <= last[0]; ++i) {
          if (!small) {
            const Eigen::Vector3d c = grid.origin + coarse_h * Eigen::Vector3d(static_cast<double>(i), static_cast<double>(j), static_cast<double>(k));
            const double m = reach + 1e-9 * coarse_h;
            if (!CGAL::do_intersect(t, CGAL::Bbox_3(c.x() - m, c.y() - m, c.z() - m, c.x() + coarse_h + m, c.y() + coarse_h + m, c.z() + coarse_h + m)))
              continue;
          }
          out.push_back(grid.key(ratio * i, ratio * j, ratio * k));
          constexpr std::size_t kCounted = 4096;
          if (!parallel) {
            if (out.size() > max_listed) merge_cells(out);
          } else if (out.size() % kCounted == 0 && listed_in_block.fetch_add(kCounted) + kCounted > max_listed) {
            block_full = true;
            return false;
          }
        }
      }
    return true;
  };
  constexpr std::size_t kListingBlock = 1 << 15;
  for (std::size_t block = 0; block < triangles.size(); block += kListingBlock) {
    const std::size_t block_end = std::min(triangles.size(), block + kListingBlock);
    listed_in_block = 0;
    block_full = false;
    {
      tbb::enumerable_thread_specific<std::vector<std::uint64_t>> listed;
      tbb::parallel_for(tbb::blocked_range<std::size_t>(block, block_end, 256), [&](const tbb::blocked_range<std::size_t>& r) {
        std::vector<std::uint64_t>& out = listed.local();
        for (std::size_t t = r.begin(); t != r.end(); ++t)
          if (!list_cells_of(triangles[t], out, true)) return;
      });
      if (!block_full) {
        std::vector<std::uint64_t> part;
        for (const std::vector<std::uint64_t>& listing : listed) part.insert(part.end(), listing.begin(), listing.end());
        merge_cells(part);
        continue;
      }
    }
    std::vector<std::uint64_t> part;
    for (std::size_t t = block; t < block_end; ++t) list_cells_of(triangles[t], part, false);
    merge_cells(part);
  }
  std::unordered_set<std::uint64_t> cells(cell_list.begin(), cell_list.end());
  cell_list.clear();
  stats.seconds_refine = seconds_since(grid_start);

  // The superset's triangles of nonzero area in a tree: the crossings below, and the edges no
  // sheet comes near in the classification.
  std::vector<ContourTriangle> proper_triangles;
  std::vector<std::size_t> proper_source;
  for (std::size_t t = 0; t < triangles.size(); ++t)
    if (!triangles[t].is_degenerate()) {
      proper_triangles.push_back(triangles[t]);
      proper_source.push_back(t);
    }
  if (proper_triangles.empty()) throw InvalidInput("the superset has no triangle of nonzero area", "superset");
  const TriangleBuckets buckets(proper_triangles, coarse_h);
  // CGAL's tree only for the closest triangle to a crossing that found no sheet: rare, so built
  // when first needed.
  std::optional<ContourTree> closest_tree;
  std::once_flag closest_tree_built;
  auto closest_triangle = [&](const Eigen::Vector3d& p) {
    std::call_once(closest_tree_built, [&] {
      closest_tree.emplace(proper_triangles.cbegin(), proper_triangles.cend());
      closest_tree->build();
      closest_tree->accelerate_distance_queries();
    });
    const auto closest = closest_tree->closest_point_and_primitive(ContourPoint(p.x(), p.y(), p.z()));
    return static_cast<std::size_t>(closest.second - proper_triangles.cbegin());
  };

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
  // The checks (crease points, refinement, verification) are made again in every repair round
  // and adaptation, mostly of unchanged parts, so they ask the same points again: their answers
  // are remembered by the point's exact coordinates (the test is deterministic). The grid's
  // corners and crossings are asked once each and need no memory.
  tbb::concurrent_unordered_map<std::array<double, 3>, signed char, ExactDoublesHash> remembered;
  std::atomic<std::int64_t> remembered_queries{0};
  // Crease points likewise: a grid adaptation plans every cell's fans again, and the cells it
  // did not split ask for the same crease points from the same inputs (sheet_crease_point is
  // deterministic); on Figs. 5 and 8 those repeated Newton solves were 90 % of the planning.
  tbb::concurrent_unordered_map<CreaseKey, CreaseAnswer, ExactDoublesHash> remembered_creases;
  auto checked_inside = [&](const Eigen::Vector3d& x) -> std::optional<bool> {
    // + 0.0 makes -0 and +0 one key.
    const std::array<double, 3> key{x.x() + 0.0, x.y() + 0.0, x.z() + 0.0};
    if (const auto it = remembered.find(key); it != remembered.end()) {
      ++remembered_queries;
      return it->second < 0 ? std::nullopt : std::optional<bool>(it->second == 1);
    }
    ++queries;
    const std::optional<bool> answer = inside(x);
    remembered.emplace(key, static_cast<signed char>(answer ? (*answer ? 1 : 0) : -1));
    return answer;
  };
  auto offset_key = [&](std::uint64_t key, std::int64_t di, std::int64_t dj, std::int64_t dk) {
    const auto i = grid.index(key);
    return grid.key(i[0] + di, i[1] + dj, i[2] + dk);
  };
  auto corner_key = [&](std::uint64_t cell, int c, std::int64_t size) {
    return offset_key(cell, size * (c & 1), size * ((c >> 1) & 1), size * ((c >> 2) & 1));
  };
  std::int64_t inferred = 0;
  // Labels the lattice points `fresh` (sorted, unique, entered in `label` but not labelled yet).
  // With `infer_labels`, their neighbours `step` lattice steps away along the axes take part.
  auto label_points = [&](const std::vector<std::uint64_t>& fresh, std::int64_t step) {
    std::vector<char> values(fresh.size());
    if (!options.infer_labels) {
      tbb::parallel_for(std::size_t{0}, fresh.size(), [&](std::size_t q) { values[q] = is_inside(grid.point(fresh[q])) ? 1 : 0; });
    } else {
      // Membership changes only across the boundary, which lies on the sheets, which lie within
      // `reach` of the superset's triangles (the assumption that chose the cells above): the two
      // ends of a grid edge whose box grown by `reach` meets no triangle share their label. So
      // the corners joined by such free edges form components with one label each: a component
      // that touches a corner labelled before takes its label, any other is asked at its first
      // and last corner (in key order), and where two answers disagree (the assumption failed)
      // every corner of it is asked.
      const auto fresh_at = [&](std::uint64_t key) -> std::ptrdiff_t {
        const auto it = std::lower_bound(fresh.begin(), fresh.end(), key);
        return it != fresh.end() && *it == key ? it - fresh.begin() : -1;
      };
      // Per fresh corner and axis direction: 0 no free edge, 1 a free edge to a fresh corner,
      // 2 / 3 a free edge to a corner labelled outside / inside before.
      std::vector<std::array<char, 6>> link(fresh.size());
      tbb::parallel_for(std::size_t{0}, fresh.size(), [&](std::size_t q) {
        const auto i = grid.index(fresh[q]);
        const Eigen::Vector3d x = grid.point(fresh[q]);
        for (int axis = 0; axis < 3; ++axis)
          for (int side = 0; side < 2; ++side) {
            char& l = link[q][static_cast<std::size_t>(2 * axis + side)];
            l = 0;
            std::array<std::int64_t, 3> j = i;
            j[static_cast<std::size_t>(axis)] += side ? step : -step;
            if (j[static_cast<std::size_t>(axis)] < 0 || j[static_cast<std::size_t>(axis)] >= grid.n[static_cast<std::size_t>(axis)]) continue;
            const std::uint64_t neighbour = grid.key(j[0], j[1], j[2]);
            char kind = 0;
            if (fresh_at(neighbour) >= 0) {
              if (!side) continue;  // the edge is tested from its lower end
              kind = 1;
            } else if (const auto it = label.find(neighbour); it != label.end() && it->second >= 0) {
              kind = static_cast<char>(2 + it->second);
            } else {
              continue;
            }
            const Eigen::Vector3d y = grid.point(neighbour);
            const double m = reach + 1e-9 * grid.h;
            const CGAL::Bbox_3 box(std::min(x.x(), y.x()) - m, std::min(x.y(), y.y()) - m, std::min(x.z(), y.z()) - m,
                                   std::max(x.x(), y.x()) + m, std::max(x.y(), y.y()) + m, std::max(x.z(), y.z()) + m);
            if (!buckets.any_meets(box)) l = kind;
          }
      });
      std::vector<std::size_t> parent(fresh.size());
      std::iota(parent.begin(), parent.end(), std::size_t{0});
      const auto find = [&](std::size_t a) {
        while (parent[a] != a) a = parent[a] = parent[parent[a]];
        return a;
      };
      for (std::size_t q = 0; q < fresh.size(); ++q) {
        const auto i = grid.index(fresh[q]);
        for (int axis = 0; axis < 3; ++axis) {
          if (link[q][static_cast<std::size_t>(2 * axis + 1)] != 1) continue;
          std::array<std::int64_t, 3> j = i;
          j[static_cast<std::size_t>(axis)] += step;
          const auto r = static_cast<std::size_t>(fresh_at(grid.key(j[0], j[1], j[2])));
          parent[find(q)] = find(r);
        }
      }
      // Per component: the labels its corners see across free edges (bit 0 outside, bit 1
      // inside), its first and last corner.
      std::vector<char> seen(fresh.size(), 0);
      std::vector<std::size_t> first(fresh.size(), fresh.size()), last(fresh.size(), 0);
      for (std::size_t q = 0; q < fresh.size(); ++q) {
        const std::size_t root = find(q);
        for (char l : link[q])
          if (l >= 2) seen[root] = static_cast<char>(seen[root] | (1 << (l - 2)));
        first[root] = std::min(first[root], q);
        last[root] = std::max(last[root], q);
      }
      std::vector<std::size_t> asked;
      for (std::size_t q = 0; q < fresh.size(); ++q)
        if (find(q) == q && (seen[q] == 0 || seen[q] == 3)) {
          asked.push_back(first[q]);
          if (last[q] != first[q]) asked.push_back(last[q]);
        }
      std::sort(asked.begin(), asked.end());
      std::vector<char> answer(fresh.size(), -1);
      tbb::parallel_for(std::size_t{0}, asked.size(), [&](std::size_t a) { answer[asked[a]] = is_inside(grid.point(fresh[asked[a]])) ? 1 : 0; });
      // The label of each component, or -1 where its corners must all be asked.
      std::vector<char> component(fresh.size(), -1);
      for (std::size_t q = 0; q < fresh.size(); ++q) {
        if (find(q) != q) continue;
        if (seen[q] == 1 || seen[q] == 2) component[q] = static_cast<char>(seen[q] - 1);
        else if (seen[q] == 0 && answer[first[q]] == answer[last[q]]) component[q] = answer[first[q]];
      }
      std::vector<std::size_t> rest;
      for (std::size_t q = 0; q < fresh.size(); ++q) {
        const char c = component[find(q)];
        if (c >= 0) values[q] = c;
        else if (answer[q] >= 0) values[q] = answer[q];
        else rest.push_back(q);
      }
      tbb::parallel_for(std::size_t{0}, rest.size(), [&](std::size_t a) { values[rest[a]] = is_inside(grid.point(fresh[rest[a]])) ? 1 : 0; });
      inferred += static_cast<std::int64_t>(fresh.size() - asked.size() - rest.size());
    }
    for (std::size_t q = 0; q < fresh.size(); ++q) label[fresh[q]] = values[q];
  };
  // Enters the points of `keys` not labelled yet and labels them.
  auto label_all = [&](std::vector<std::uint64_t> keys, std::int64_t step) {
    // In key order (rows along x, then y, then z), so that a thread's consecutive queries are
    // grid neighbours and a membership test that starts from its last answer (image_membership.h)
    // starts next door.
    tbb::parallel_sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    std::vector<std::uint64_t> fresh;
    for (std::uint64_t k : keys)
      if (label.try_emplace(k, -1).second) fresh.push_back(k);
    label_points(fresh, step);
  };
  std::vector<std::uint64_t> frontier(cells.begin(), cells.end());
  while (!frontier.empty()) {
    std::vector<std::uint64_t> corners;
    corners.reserve(8 * frontier.size());
    for (std::uint64_t cell : frontier)
      for (int c = 0; c < 8; ++c) corners.push_back(corner_key(cell, c, ratio));
    label_all(std::move(corners), ratio);
    std::vector<std::uint64_t> grown;
    for (std::uint64_t cell : frontier) {
      const auto i = grid.index(cell);
      for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side) {
          std::array<std::int64_t, 3> j = i;
          j[static_cast<std::size_t>(axis)] += side ? ratio : -ratio;
          if (j[static_cast<std::size_t>(axis)] < 0 || j[static_cast<std::size_t>(axis)] > grid.n[static_cast<std::size_t>(axis)] - 1 - ratio) continue;
          const std::uint64_t neighbour = grid.key(j[0], j[1], j[2]);
          if (cells.count(neighbour)) continue;
          int in = 0;
          for (int c = 0; c < 8; ++c)
            if (((c >> axis) & 1) == side) in += label.at(corner_key(cell, c, ratio));
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

  // Marching tetrahedra: one polygon per tetrahedron with mixed corners, a cycle of 3 or 4
  // crossed lattice edges (inside corner, outside corner), oriented from inside to outside on the
  // edges' midpoints (the level set at 1/2 of the linear interpolant of the labels, whose
  // orientation moving the vertices along their edges does not change).
  struct LatticeEdgeHash {
    std::size_t operator()(const std::pair<std::uint64_t, std::uint64_t>& e) const {
      return std::hash<std::uint64_t>{}(e.first * 0x9e3779b97f4a7c15ull ^ e.second);
    }
  };
  std::unordered_map<std::pair<std::uint64_t, std::uint64_t>, int, LatticeEdgeHash> edge_vertex;
  std::vector<std::pair<std::uint64_t, std::uint64_t>> edges;
  std::vector<ContourPolygon> polygons;
  std::vector<ContourCell> cell_of;
  auto edge_id = [&](std::uint64_t a, std::uint64_t b) {
    const auto [it, fresh] = edge_vertex.try_emplace({a, b}, static_cast<int>(edges.size()));
    if (fresh) edges.emplace_back(a, b);
    return it->second;
  };
  auto lattice_point = [&](std::uint64_t key) {
    const auto i = grid.index(key);
    return Eigen::Vector3d(static_cast<double>(i[0]), static_cast<double>(i[1]), static_cast<double>(i[2]));
  };
  auto march = [&](const std::array<std::uint64_t, 4>& tet, std::uint64_t cell, std::vector<ContourPolygon>& out) {
    std::array<int, 4> ins{}, outs{};
    std::size_t n_in = 0, n_out = 0;
    for (int c = 0; c < 4; ++c) {
      if (label.at(tet[static_cast<std::size_t>(c)])) ins[n_in++] = c;
      else outs[n_out++] = c;
    }
    if (n_in == 0 || n_out == 0) return;
    std::array<Eigen::Vector3d, 4> corner;
    for (int c = 0; c < 4; ++c) corner[static_cast<std::size_t>(c)] = lattice_point(tet[static_cast<std::size_t>(c)]);
    Eigen::Vector3d in_centre = Eigen::Vector3d::Zero(), out_centre = Eigen::Vector3d::Zero();
    for (std::size_t k = 0; k < n_in; ++k) in_centre += corner[static_cast<std::size_t>(ins[k])] / static_cast<double>(n_in);
    for (std::size_t k = 0; k < n_out; ++k) out_centre += corner[static_cast<std::size_t>(outs[k])] / static_cast<double>(n_out);
    const Eigen::Vector3d outward = out_centre - in_centre;
    std::array<std::pair<int, int>, 4> cycle{};
    std::size_t cycle_size = 3;
    if (n_in == 1) cycle = {{{ins[0], outs[0]}, {ins[0], outs[1]}, {ins[0], outs[2]}, {}}};
    else if (n_out == 1) cycle = {{{ins[0], outs[0]}, {ins[1], outs[0]}, {ins[2], outs[0]}, {}}};
    else {
      cycle = {{{ins[0], outs[0]}, {ins[0], outs[1]}, {ins[1], outs[1]}, {ins[1], outs[0]}}};
      cycle_size = 4;
    }
    auto mid = [&](const std::pair<int, int>& p) {
      return Eigen::Vector3d(0.5 * (corner[static_cast<std::size_t>(p.first)] + corner[static_cast<std::size_t>(p.second)]) - in_centre);
    };
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    for (std::size_t j = 0; j < cycle_size; ++j) normal += mid(cycle[j]).cross(mid(cycle[(j + 1) % cycle_size]));
    if (normal.dot(outward) < 0) std::reverse(cycle.begin(), cycle.begin() + static_cast<std::ptrdiff_t>(cycle_size));
    // The crossed edges as corner pairs 4 i + o (numbered by march_cells).
    ContourPolygon polygon;
    polygon.count = static_cast<int>(cycle_size);
    for (std::size_t j = 0; j < cycle_size; ++j) polygon.vertex[j] = 4 * cycle[j].first + cycle[j].second;
    polygon.cell = cell;
    polygon.tetrahedron = tet;
    out.push_back(polygon);
  };
  // The six Kuhn tetrahedra of a cube `size` lattice steps wide.
  auto march_cube = [&](std::uint64_t low, std::int64_t size, std::uint64_t cell, std::vector<ContourPolygon>& out) {
    for (const auto& tet : kKuhnTetrahedra) {
      std::array<std::uint64_t, 4> keys{};
      for (int c = 0; c < 4; ++c) keys[static_cast<std::size_t>(c)] = corner_key(low, tet[static_cast<std::size_t>(c)], size);
      march(keys, cell, out);
    }
  };
  // Marches the cells `list` (cell number: cell_of's size before the call + index) in parallel,
  // in chunks, and numbers the edges in list order: the same cells, polygons and edge numbers
  // as one serial pass. march_entry(k, cell, out) marches list[k]'s tetrahedra.
  auto march_cells = [&](const std::vector<std::pair<std::uint64_t, std::int64_t>>& list, const auto& march_entry) {
    const auto first_cell = static_cast<std::uint64_t>(cell_of.size());
    for (const auto& entry : list) cell_of.push_back({entry.first, entry.second});
    constexpr std::size_t kChunk = 256;
    std::vector<std::vector<ContourPolygon>> chunks((list.size() + kChunk - 1) / kChunk);
    tbb::parallel_for(std::size_t{0}, chunks.size(), [&](std::size_t c) {
      for (std::size_t k = c * kChunk; k < std::min(list.size(), (c + 1) * kChunk); ++k) march_entry(k, first_cell + k, chunks[c]);
    });
    for (const std::vector<ContourPolygon>& chunk : chunks)
      for (ContourPolygon polygon : chunk) {
        for (int j = 0; j < polygon.count; ++j) {
          int& v = polygon.vertex[static_cast<std::size_t>(j)];
          v = edge_id(polygon.tetrahedron[static_cast<std::size_t>(v / 4)], polygon.tetrahedron[static_cast<std::size_t>(v % 4)]);
        }
        polygons.push_back(polygon);
      }
  };
  std::vector<std::uint64_t> sorted_cells(cells.begin(), cells.end());
  std::sort(sorted_cells.begin(), sorted_cells.end());
  {
    std::vector<std::pair<std::uint64_t, std::int64_t>> grid_cells;
    grid_cells.reserve(sorted_cells.size());
    for (std::uint64_t cell : sorted_cells) grid_cells.emplace_back(cell, ratio);
    march_cells(grid_cells, [&](std::size_t k, std::uint64_t cell, std::vector<ContourPolygon>& out) {
      march_cube(grid_cells[k].first, grid_cells[k].second, cell, out);
    });
  }

  // The crossings: the superset's intersections with the edge, sorted along it; between the
  // inside end and the outside end, the crossing after the last stretch found inside (binary
  // search over the stretches between crossings), which brackets the boundary between the last
  // probe inside and the first outside. With the sheets' equations the vertex goes onto the
  // sheet of that crossing (or of the next one in the bracket), and when none crosses inside the
  // bracket (the superset's chords passed the edge by), the bracket is bisected and the sheets
  // near its end are tried there. Off every sheet: the bisection point.
  // Zero-area triangles of the superset cannot be crossed (and CGAL's segment-triangle
  // intersection requires a proper triangle): the tree holds the others, mapped back by index.
  // The crossings of every lattice edge met so far (by edge id), and those of the complex's edges.
  std::vector<ContourCrossing> all_crossings, crossings;
  auto cross_edge = [&](std::size_t e) {
    const Eigen::Vector3d a = grid.point(edges[e].first), b = grid.point(edges[e].second);
    const Eigen::Vector3d ab = b - a;
    std::vector<std::pair<double, std::size_t>> along;
    auto add = [&](const ContourPoint& p, std::size_t t) {
      along.emplace_back(std::clamp((Eigen::Vector3d(p.x(), p.y(), p.z()) - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0), t);
    };
    const ContourKernel::Segment_3 segment(ContourPoint(a.x(), a.y(), a.z()), ContourPoint(b.x(), b.y(), b.z()));
    buckets.visit_candidates(segment.bbox(), [&](std::size_t i) {
      const auto hit = CGAL::intersection(segment, proper_triangles[i]);
      if (!hit) return true;
      const std::size_t t = proper_source[i];
      if (const auto* p = boost::get<ContourPoint>(&*hit)) add(*p, t);
      else if (const auto* q = boost::get<ContourKernel::Segment_3>(&*hit)) add(CGAL::midpoint(q->source(), q->target()), t);
      return true;
    });
    std::sort(along.begin(), along.end());
    // Crossings closer than this are one (coincident sheets).
    const double merge = 1e-6;
    std::vector<std::pair<double, std::size_t>> distinct;
    for (const auto& h : along)
      if (distinct.empty() || h.first - distinct.back().first > merge) distinct.push_back(h);
    ContourCrossing& x = all_crossings[e];
    // The boundary lies in [low, high]: a is inside, b outside, and so are the probes.
    double low = 0, high = 1, lambda = 0.5;
    bool found = false;
    if (!distinct.empty()) {
      // Stretch s lies between crossing s - 1 and crossing s; stretch 0 is inside, the last outside.
      std::size_t in_stretch = 0, out_stretch = distinct.size();
      while (out_stretch - in_stretch > 1) {
        const std::size_t mid = (in_stretch + out_stretch) / 2;
        const double probe = 0.5 * (distinct[mid - 1].first + distinct[mid].first);
        if (is_inside(a + probe * ab)) {
          in_stretch = mid;
          low = probe;
        } else {
          out_stretch = mid;
          high = probe;
        }
      }
      lambda = distinct[in_stretch].first;
      x.triangle = distinct[in_stretch].second;
      found = true;
    }
    auto try_sheet = [&](std::size_t t, double start, double from, double to) {
      const Eigen::Vector3d bary = contour_barycentric(a + start * ab, triangles[t]);
      const std::optional<SheetCrossing> c = sheet_crossing(t, bary, start, a, b);
      if (!c || c->lambda < from || c->lambda > to) return false;
      x.triangle = t;
      x.on_sheet = true;
      x.lambda = c->lambda;
      x.parameters = c->parameters;
      x.extra = c->extra;
      x.normal = c->normal;
      return true;
    };
    if (sheet_crossing) {
      const double slack = 1e-9;
      bool placed = false;
      {
        // Every sheet crossing the bracket (the chosen crossing first, then the others, nearest
        // first), on the sheet; where several remain at distinct places (a sheet inside S
        // passing near, or tangent to, the boundary), membership tests between them choose
        // as above.
        std::vector<std::tuple<double, double, std::size_t>> candidates;
        for (const auto& h : along)
          if (h.first >= low && h.first <= high)
            candidates.emplace_back(found && h.second == x.triangle ? -1.0 : std::abs(h.first - lambda), h.first, h.second);
        std::sort(candidates.begin(), candidates.end());
        // Sheets within reach of the edge whose chords miss it (a fold tangent to a cap, say)
        // are tried too, from their triangle nearest the edge.
        if (!sheet_of_triangle.empty()) {
          const double r = reach;
          const CGAL::Bbox_3 box(std::min(a.x(), b.x()) - r, std::min(a.y(), b.y()) - r, std::min(a.z(), b.z()) - r,
                                 std::max(a.x(), b.x()) + r, std::max(a.y(), b.y()) + r, std::max(a.z(), b.z()) + r);
          std::map<int, std::pair<double, std::size_t>> nearest_of_sheet;
          std::set<int> crossing_sheets;
          for (const auto& c : candidates) crossing_sheets.insert(sheet_of_triangle[std::get<2>(c)]);
          const Eigen::Vector3d middle = 0.5 * (a + b);
          const ContourPoint centre(middle.x(), middle.y(), middle.z());
          const double within = r + 0.5 * std::sqrt(ab.squaredNorm());
          buckets.visit_meeting(box, [&](std::size_t id) {
            const std::size_t t = proper_source[id];
            const int sheet = sheet_of_triangle[t];
            if (crossing_sheets.count(sheet)) return true;
            const double d = CGAL::squared_distance(centre, triangles[t]);
            if (d > within * within) return true;
            const auto [it, fresh] = nearest_of_sheet.try_emplace(sheet, d, t);
            if (!fresh && std::make_pair(d, t) < it->second) it->second = {d, t};
            return true;
          });
          for (const auto& [sheet, near] : nearest_of_sheet) {
            const ContourTriangle& tri = triangles[near.second];
            const Eigen::Vector3d centroid((tri[0].x() + tri[1].x() + tri[2].x()) / 3, (tri[0].y() + tri[1].y() + tri[2].y()) / 3,
                                           (tri[0].z() + tri[1].z() + tri[2].z()) / 3);
            candidates.emplace_back(2.0, std::clamp((centroid - a).dot(ab) / ab.squaredNorm(), low, high), near.second);
          }
        }
        std::set<std::size_t> tried;
        std::set<int> tried_sheets;
        std::vector<std::pair<SheetCrossing, std::size_t>> on_sheets;
        for (const auto& [order, start, t] : candidates) {
          if (tried.size() >= 8) break;
          if (!tried.insert(t).second) continue;
          if (!sheet_of_triangle.empty() && !tried_sheets.insert(sheet_of_triangle[t]).second) continue;
          const Eigen::Vector3d bary = contour_barycentric(a + start * ab, triangles[t]);
          const std::optional<SheetCrossing> c = sheet_crossing(t, bary, start, a, b);
          if (c && c->lambda >= low - slack && c->lambda <= high + slack) on_sheets.emplace_back(*c, t);
        }
        std::stable_sort(on_sheets.begin(), on_sheets.end(), [](const auto& p, const auto& q) { return p.first.lambda < q.first.lambda; });
        std::vector<std::pair<SheetCrossing, std::size_t>> apart;
        for (const auto& c : on_sheets)
          if (apart.empty() || c.first.lambda - apart.back().first.lambda > 1e-9) apart.push_back(c);
        if (!apart.empty()) {
          std::size_t in_stretch = 0, out_stretch = apart.size();
          while (out_stretch - in_stretch > 1) {
            const std::size_t mid = (in_stretch + out_stretch) / 2;
            const double probe = 0.5 * (apart[mid - 1].first.lambda + apart[mid].first.lambda);
            (is_inside(a + probe * ab) ? in_stretch : out_stretch) = mid;
          }
          const SheetCrossing& c = apart[in_stretch].first;
          // Where the sheet of the superset crossing the membership tests chose gave no crossing
          // in the bracket and another sheet's crossing is taken instead, the stretches before
          // and after it that no probe has looked at yet are probed: a sheet near the edge whose
          // chords miss it may lie inside S (the swept seam of a ball beside the line of its
          // pole) while Newton on the sheet that bounds S there failed; then the boundary is
          // bisected below. (Where no superset triangle crosses the edge at all the crossing is
          // taken unprobed: probing those too cost 35 % more membership queries on Fig. 4.)
          const auto sheet_of = [&](std::size_t t) { return sheet_of_triangle.empty() ? static_cast<int>(t) : sheet_of_triangle[t]; };
          bool chosen_sheet_crossed = false;
          for (const auto& on : apart) chosen_sheet_crossed = chosen_sheet_crossed || (found && sheet_of(on.second) == sheet_of(x.triangle));
          bool consistent = true;
          if (found && !chosen_sheet_crossed) {
            if (out_stretch == apart.size()) {
              const double after = 0.5 * (c.lambda + high);
              if (is_inside(a + after * ab)) {
                low = std::max(low, after);
                consistent = false;
              }
            }
            if (consistent && in_stretch == 0) {
              const double before = 0.5 * (low + c.lambda);
              if (!is_inside(a + before * ab)) {
                high = std::min(high, before);
                consistent = false;
              }
            }
          }
          if (consistent) {
            x.triangle = apart[in_stretch].second;
            x.on_sheet = true;
            x.lambda = c.lambda;
            x.parameters = c.parameters;
            x.extra = c.extra;
            x.normal = c.normal;
            placed = true;
          }
        }
      }
      if (!placed) {
        for (int s = 0; s < options.bisection_steps + 8; ++s) {
          const double m = 0.5 * (low + high);
          (is_inside(a + m * ab) ? low : high) = m;
        }
        const Eigen::Vector3d p = a + 0.5 * (low + high) * ab;
        const double r = reach + (high - low) * std::sqrt(ab.squaredNorm());
        std::vector<std::size_t> near;
        buckets.visit_meeting(CGAL::Bbox_3(p.x() - r, p.y() - r, p.z() - r, p.x() + r, p.y() + r, p.z() + r), [&](std::size_t id) {
          near.push_back(proper_source[id]);
          return true;
        });
        const ContourPoint cp(p.x(), p.y(), p.z());
        std::vector<std::pair<double, std::size_t>> by_distance;
        for (std::size_t t : near) by_distance.emplace_back(CGAL::squared_distance(cp, triangles[t]), t);
        std::sort(by_distance.begin(), by_distance.end());
        const double margin = (high - low) + slack;
        for (std::size_t q = 0; q < by_distance.size() && q < 24 && !placed; ++q)
          placed = try_sheet(by_distance[q].second, 0.5 * (low + high), low - margin, high + margin);
        if (placed) {
          x.after_bisection = true;
        } else {
          lambda = 0.5 * (low + high);
          found = false;
        }
      }
      if (placed) {
        lambda = x.lambda;
      }
    } else if (!found) {
      for (int s = 0; s < options.bisection_steps; ++s) {
        const double m = 0.5 * (low + high);
        (is_inside(a + m * ab) ? low : high) = m;
      }
      lambda = 0.5 * (low + high);
    }
    if (!x.on_sheet && !found) {
      const Eigen::Vector3d p = a + lambda * ab;
      x.triangle = proper_source[closest_triangle(p)];
      x.off_superset = true;
    }
    // Strictly inside the edge, so that no triangle degenerates.
    lambda = std::clamp(lambda, 1e-6, 1 - 1e-6);
    x.position = a + lambda * ab;
    x.barycentric = contour_barycentric(x.position, triangles[x.triangle]);
  };
  auto cross_new_edges = [&]() {
    const std::size_t from = all_crossings.size();
    all_crossings.resize(edges.size());
    tbb::parallel_for(from, edges.size(), cross_edge);
  };
  cross_new_edges();

  // Adaptive cells (coarse_ratio > 1), an octree: a coarse cell where the contour bends by more
  // than the crease angle or a vertex found no sheet is split into halves (eight cells ratio / 2
  // wide), each of those where the contour still bends into halves again, and so on down to cells
  // of `cell_size` (where a half would be odd, ratio 6 say, straight into unit cells). A crease
  // is a curve: of the 64 unit cells of a coarse cell it passes, it bends the contour in a few
  // (Fig. 5: 1,411 of 66,112), so splitting by halves keeps most of the coarse cell at twice the
  // unit width (docs/envelopes.md, "Adaptive cells"). The smooth parts keep their coarse cells,
  // whose vertices lie on the sheets all the same (the refinement toward the sheets makes their
  // chords accurate). Conforming, so that the surface stays closed: every square face of the
  // complex is triangulated by a rule that depends on the face alone.
  // - The complex's vertices are its cells' corners: a lattice point is one if it is a multiple
  //   of the smallest cell size among the eight unit cubes around it (sizes divide each other).
  // - A square face is tiled by the squares of the finer of its two sides (a quadtree).
  // - A tile none of whose edges holds a vertex inside: split along the diagonal from its lowest
  //   to its highest corner (the Kuhn diagonal every cube uses); any other: a fan from its centre
  //   over its edges' vertices.
  // - A cell none of whose edges holds a vertex inside keeps its six Kuhn tetrahedra; any other
  //   (a transition cell) is coned from its centre over its faces' triangles.
  // With halving_levels off (coarse and unit cells only) this is the two-level complex of
  // before 2026-12-07, face for face.
  std::vector<std::int64_t> level_size{ratio};
  while (level_size.back() > 1) {
    const std::int64_t s = level_size.back();
    level_size.push_back(options.halving_levels && (s / 2 == 1 || (s / 2) % 2 == 0) ? s / 2 : 1);
  }
  const std::size_t levels = level_size.size();
  // split[l]: the cells level_size[l] wide split into cells level_size[l + 1] wide; split[0], the
  // coarse cells refined.
  std::vector<std::unordered_set<std::uint64_t>> split(std::max<std::size_t>(1, levels - 1));
  std::unordered_set<std::uint64_t>& refined = split[0];
  using LatticeIndex = std::array<std::int64_t, 3>;
  const auto index_key = [&](const LatticeIndex& i) { return grid.key(i[0], i[1], i[2]); };
  const auto floor_to = [](const LatticeIndex& i, std::int64_t s) { return LatticeIndex{i[0] - i[0] % s, i[1] - i[1] % s, i[2] - i[2] % s}; };
  const auto level_of = [&](std::int64_t s) {
    return static_cast<std::size_t>(std::find(level_size.begin(), level_size.end(), s) - level_size.begin());
  };
  // The width of the cell holding the unit cube whose lowest corner is u (outside the coarse
  // grid: a coarse cell).
  const auto leaf_size = [&](const LatticeIndex& u) {
    for (std::size_t d = 0; d < 3; ++d)
      if (u[d] < 0 || u[d] > grid.n[d] - 2) return level_size[0];
    for (std::size_t l = 0; l + 1 < levels; ++l)
      if (!split[l].count(index_key(floor_to(u, level_size[l])))) return level_size[l];
    return std::int64_t{1};
  };
  // The corners of the cells narrower than the coarse ones, rebuilt with the complex. The
  // complex's vertices are the coarse lattice points and these.
  std::unordered_set<std::uint64_t> fine_vertices;
  const auto is_vertex = [&](const LatticeIndex& q) {
    return (q[0] % ratio == 0 && q[1] % ratio == 0 && q[2] % ratio == 0) || fine_vertices.count(index_key(q)) > 0;
  };
  // The complex's vertices strictly inside the segment `length` steps from p along `axis`,
  // appended from p onward (backward: from the far end back).
  const auto edge_vertices = [&](const LatticeIndex& p, int axis, std::int64_t length, bool backward, std::vector<std::uint64_t>* out) {
    bool any = false;
    for (std::int64_t k = 1; k < length; ++k) {
      LatticeIndex q = p;
      q[static_cast<std::size_t>(axis)] += backward ? length - k : k;
      if (!is_vertex(q)) continue;
      if (!out) return true;
      any = true;
      out->push_back(index_key(q));
    }
    return any;
  };
  const auto lattice_of = [&](std::uint64_t key) { return grid.index(key); };
  // The coarse cells next to a refined one (itself included), rebuilt with the complex: any
  // other keeps its Kuhn tetrahedra and plain faces without looking further.
  std::unordered_set<std::uint64_t> near_refined;
  const auto coarse_cell_in_grid = [&](const LatticeIndex& j) {
    for (std::size_t d = 0; d < 3; ++d)
      if (j[d] < 0 || j[d] > grid.n[d] - 1 - ratio) return false;
    return true;
  };
  const auto far_from_refined = [&](const LatticeIndex& low) { return coarse_cell_in_grid(low) && !near_refined.count(index_key(low)); };
  const std::array<std::uint64_t, 3> unit_step{grid.key(1, 0, 0), grid.key(0, 1, 0), grid.key(0, 0, 1)};
  // The tiles of the square face of lowest corner p, `width` steps wide, across `axis`.
  const auto face_tiles = [&](const LatticeIndex& p, int axis, std::int64_t width, std::vector<std::pair<LatticeIndex, std::int64_t>>& out) {
    const int b = std::min((axis + 1) % 3, (axis + 2) % 3), c = std::max((axis + 1) % 3, (axis + 2) % 3);
    std::vector<std::pair<LatticeIndex, std::int64_t>> todo{{p, width}};
    while (!todo.empty()) {
      const auto [q, s] = todo.back();
      todo.pop_back();
      // A square is split (the cells on one side narrower) exactly where its centre is a vertex.
      LatticeIndex centre = q;
      centre[static_cast<std::size_t>(b)] += s / 2;
      centre[static_cast<std::size_t>(c)] += s / 2;
      if (s == 1 || !is_vertex(centre)) {
        out.emplace_back(q, s);
        continue;
      }
      const std::int64_t next = level_size[level_of(s) + 1];
      // Pushed last to first, so that they come out in rows along b, then c.
      for (std::int64_t v = s / next - 1; v >= 0; --v)
        for (std::int64_t u = s / next - 1; u >= 0; --u) {
          LatticeIndex r = q;
          r[static_cast<std::size_t>(b)] += u * next;
          r[static_cast<std::size_t>(c)] += v * next;
          todo.emplace_back(r, next);
        }
    }
  };
  // The face's triangles (lattice keys) and its fans' centres; true if it is one tile on the Kuhn
  // diagonal.
  const auto face_triangles = [&](std::uint64_t p_key, int axis, std::int64_t width, std::vector<std::array<std::uint64_t, 3>>& out_triangles,
                                  std::vector<std::uint64_t>* fan_centres) {
    const int b = std::min((axis + 1) % 3, (axis + 2) % 3), c = std::max((axis + 1) % 3, (axis + 2) % 3);
    const LatticeIndex p = lattice_of(p_key);
    if (width == level_size[0] && ratio > 1) {
      // A coarse face with a side not next to a refined cell: neither side is split, and no
      // edge borders a split cell.
      LatticeIndex below = p;
      below[static_cast<std::size_t>(axis)] -= width;
      if (far_from_refined(p) || far_from_refined(below)) {
        const std::uint64_t eb = static_cast<std::uint64_t>(width) * unit_step[static_cast<std::size_t>(b)];
        const std::uint64_t ec = static_cast<std::uint64_t>(width) * unit_step[static_cast<std::size_t>(c)];
        out_triangles.push_back({p_key, p_key + eb, p_key + eb + ec});
        out_triangles.push_back({p_key, p_key + ec, p_key + eb + ec});
        return true;
      }
    }
    std::vector<std::pair<LatticeIndex, std::int64_t>> tiles;
    face_tiles(p, axis, width, tiles);
    bool plain = tiles.size() == 1;
    std::vector<std::uint64_t> loop;
    for (const auto& [q, s] : tiles) {
      LatticeIndex qb = q, qc = q, qbc = q;
      qb[static_cast<std::size_t>(b)] += s;
      qc[static_cast<std::size_t>(c)] += s;
      qbc[static_cast<std::size_t>(b)] += s;
      qbc[static_cast<std::size_t>(c)] += s;
      loop.clear();
      // Counter-clockwise in (b, c): each side's first corner, then the vertices inside it.
      loop.push_back(index_key(q));
      edge_vertices(q, b, s, false, &loop);
      loop.push_back(index_key(qb));
      edge_vertices(qb, c, s, false, &loop);
      loop.push_back(index_key(qbc));
      edge_vertices(qc, b, s, true, &loop);
      loop.push_back(index_key(qc));
      edge_vertices(q, c, s, true, &loop);
      if (loop.size() == 4) {
        out_triangles.push_back({loop[0], loop[1], loop[2]});
        out_triangles.push_back({loop[0], loop[3], loop[2]});
        continue;
      }
      plain = false;
      LatticeIndex centre = q;
      centre[static_cast<std::size_t>(b)] += s / 2;
      centre[static_cast<std::size_t>(c)] += s / 2;
      const std::uint64_t centre_key = index_key(centre);
      if (fan_centres) fan_centres->push_back(centre_key);
      for (std::size_t k = 0; k < loop.size(); ++k) out_triangles.push_back({centre_key, loop[k], loop[(k + 1) % loop.size()]});
    }
    return plain;
  };
  // A cell is coned from its centre when one of its edges holds a vertex inside.
  const auto is_transition = [&](std::uint64_t low_key, std::int64_t s) {
    if (s == 1 || (s == level_size[0] && !near_refined.count(low_key))) return false;
    const LatticeIndex low = lattice_of(low_key);
    for (int axis = 0; axis < 3; ++axis) {
      const int b = (axis + 1) % 3, c = (axis + 2) % 3;
      for (int e = 0; e < 4; ++e) {
        LatticeIndex start = low;
        start[static_cast<std::size_t>(b)] += (e & 1) * s;
        start[static_cast<std::size_t>(c)] += ((e >> 1) & 1) * s;
        if (edge_vertices(start, axis, s, false, nullptr)) return true;
      }
    }
    return false;
  };
  // The lowest corner of the face of cell `low` (`s` wide) across `axis` on `side`.
  const auto face_of = [&](std::uint64_t low, std::int64_t s, int axis, int side) {
    return side ? low + static_cast<std::uint64_t>(s) * unit_step[static_cast<std::size_t>(axis)] : low;
  };
  // The lattice points a cell's tetrahedra use (corners; fan and cone centres).
  const auto cell_points = [&](std::uint64_t cell, std::int64_t s, std::vector<std::uint64_t>& corners, std::vector<std::uint64_t>& centres) {
    if (!is_transition(cell, s)) {
      for (int c = 0; c < 8; ++c) corners.push_back(corner_key(cell, c, s));
      return;
    }
    std::vector<std::array<std::uint64_t, 3>> face;
    for (int axis = 0; axis < 3; ++axis)
      for (int side = 0; side < 2; ++side) {
        face.clear();
        face_triangles(face_of(cell, s, axis, side), axis, s, face, &centres);
        for (const auto& t : face)
          for (std::uint64_t k : t) corners.push_back(k);
      }
    centres.push_back(offset_key(cell, s / 2, s / 2, s / 2));
  };
  // The cells `size` wide among the polygons' (vertex ids: edge ids into all_crossings) where the
  // contour bends by more than the crease angle or a vertex found no sheet.
  const double crease_cos_coarse = std::cos(options.crease_angle_degrees * std::numbers::pi / 180);
  // Without the sheets' equations a crossing's normal is that of its superset triangle.
  const auto superset_normal = [&](std::size_t t) {
    const Eigen::Vector3d a(triangles[t][0].x(), triangles[t][0].y(), triangles[t][0].z());
    const Eigen::Vector3d b(triangles[t][1].x(), triangles[t][1].y(), triangles[t][1].z());
    const Eigen::Vector3d c(triangles[t][2].x(), triangles[t][2].y(), triangles[t][2].z());
    const Eigen::Vector3d n = (b - a).cross(c - a);
    return n.norm() > 0 ? Eigen::Vector3d(n.normalized()) : n;
  };
  const auto bent_cells = [&](std::int64_t size) {
    std::vector<std::pair<std::size_t, std::size_t>> groups;
    for (std::size_t first = 0; first < polygons.size();) {
      std::size_t end = first;
      while (end < polygons.size() && polygons[end].cell == polygons[first].cell) ++end;
      if (cell_of[polygons[first].cell].size == size) groups.emplace_back(first, end);
      first = end;
    }
    std::vector<char> bent(groups.size(), 0);
    tbb::parallel_for(std::size_t{0}, groups.size(), [&](std::size_t g) {
      std::vector<int> corners;
      for (std::size_t q = groups[g].first; q < groups[g].second; ++q)
        corners.insert(corners.end(), polygons[q].vertex.begin(), polygons[q].vertex.begin() + polygons[q].count);
      std::sort(corners.begin(), corners.end());
      corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
      bool refine_cell = false;
      std::vector<Eigen::Vector3d> normals;
      for (std::size_t j = 0; !refine_cell && j < corners.size(); ++j) {
        const ContourCrossing& xj = all_crossings[static_cast<std::size_t>(corners[j])];
        if (sheet_crossing && (!xj.on_sheet || xj.normal.isZero())) refine_cell = true;
        normals.push_back(xj.on_sheet ? xj.normal : superset_normal(xj.triangle));
        for (std::size_t i = 0; !refine_cell && i < j; ++i) refine_cell = std::abs(normals[j].dot(normals[i])) < crease_cos_coarse;
      }
      bent[g] = refine_cell ? 1 : 0;
    });
    std::vector<std::uint64_t> out;
    for (std::size_t g = 0; g < groups.size(); ++g)
      if (bent[g]) out.push_back(cell_of[polygons[groups[g].first].cell].low);
    return out;
  };
  if (ratio > 1)
    for (std::uint64_t cell : bent_cells(ratio)) refined.insert(cell);
  // The complex of the leaves (the cells not split), its polygons, and the crossings of their
  // edges (`crossings`, the polygons' vertex ids renumbered into it).
  // A cell's tetrahedra: Kuhn's or coned from its centre.
  const auto march_leaf = [&](std::uint64_t low, std::int64_t size, std::uint64_t cell, std::vector<ContourPolygon>& out) {
    if (!is_transition(low, size)) {
      march_cube(low, size, cell, out);
      return;
    }
    const std::uint64_t centre = offset_key(low, size / 2, size / 2, size / 2);
    std::vector<std::array<std::uint64_t, 3>> face;
    for (int axis = 0; axis < 3; ++axis)
      for (int side = 0; side < 2; ++side) {
        face.clear();
        face_triangles(face_of(low, size, axis, side), axis, size, face, nullptr);
        for (const auto& t : face) march({centre, t[0], t[1], t[2]}, cell, out);
      }
  };
  // only_width > 0: just the cells that wide inside the refined cells, for the bends below.
  auto make_complex = [&](std::int64_t only_width) {
    stats.grid_cells_refined = static_cast<std::int64_t>(refined.size());
    std::vector<std::uint64_t> sorted_refined(refined.begin(), refined.end());
    std::sort(sorted_refined.begin(), sorted_refined.end());
    const auto& cell_in_grid = coarse_cell_in_grid;
    near_refined.clear();
    for (std::uint64_t cell : sorted_refined) {
      const auto i = grid.index(cell);
      for (std::int64_t dk = -1; dk <= 1; ++dk)
        for (std::int64_t dj = -1; dj <= 1; ++dj)
          for (std::int64_t di = -1; di <= 1; ++di) {
            const std::array<std::int64_t, 3> j{i[0] + ratio * di, i[1] + ratio * dj, i[2] + ratio * dk};
            if (cell_in_grid(j)) near_refined.insert(grid.key(j[0], j[1], j[2]));
          }
    }
    // The leaves inside the refined cells, level by level, and their lattice points.
    std::vector<std::pair<std::uint64_t, std::int64_t>> fine_leaves;
    {
      std::vector<std::uint64_t> parents = sorted_refined;
      for (std::size_t l = 1; l < levels; ++l) {
        const std::int64_t s = level_size[l], n = level_size[l - 1] / s;
        std::vector<std::uint64_t> next_parents;
        for (std::uint64_t parent : parents)
          for (std::int64_t k = 0; k < n; ++k)
            for (std::int64_t j = 0; j < n; ++j)
              for (std::int64_t i = 0; i < n; ++i) {
                const std::uint64_t child = offset_key(parent, i * s, j * s, k * s);
                if (l + 1 < levels && split[l].count(child)) next_parents.push_back(child);
                else fine_leaves.emplace_back(child, s);
              }
        parents = std::move(next_parents);
      }
    }
    fine_vertices.clear();
    for (const auto& [cell, size] : fine_leaves)
      for (int c = 0; c < 8; ++c) fine_vertices.insert(corner_key(cell, c, size));
    constexpr std::size_t kLeafChunk = 256;
    for (std::size_t l = levels; l-- > 1;) {
      const std::int64_t s = level_size[l];
      std::vector<std::uint64_t> leaves;
      for (const auto& [cell, size] : fine_leaves)
        if (size == s) leaves.push_back(cell);
      const std::size_t n_chunks = (leaves.size() + kLeafChunk - 1) / kLeafChunk;
      std::vector<std::vector<std::uint64_t>> chunk_corners(n_chunks), chunk_centres(n_chunks);
      tbb::parallel_for(std::size_t{0}, n_chunks, [&](std::size_t c) {
        for (std::size_t k = c * kLeafChunk; k < std::min(leaves.size(), (c + 1) * kLeafChunk); ++k)
          cell_points(leaves[k], s, chunk_corners[c], chunk_centres[c]);
      });
      std::vector<std::uint64_t> corners, centres;
      for (std::size_t c = 0; c < n_chunks; ++c) {
        corners.insert(corners.end(), chunk_corners[c].begin(), chunk_corners[c].end());
        centres.insert(centres.end(), chunk_centres[c].begin(), chunk_centres[c].end());
      }
      label_all(std::move(corners), s);
      if (s > 1) label_all(std::move(centres), s / 2);
    }
    if (only_width > 0) {
      polygons.clear();
      cell_of.clear();
      std::vector<std::pair<std::uint64_t, std::int64_t>> leaves;
      for (const auto& leaf : fine_leaves)
        if (leaf.second == only_width) leaves.push_back(leaf);
      std::sort(leaves.begin(), leaves.end());
      march_cells(leaves, [&](std::size_t k, std::uint64_t cell, std::vector<ContourPolygon>& out) { march_leaf(leaves[k].first, leaves[k].second, cell, out); });
      cross_new_edges();
      return;
    }
    // Coarse cells of the complex: the unrefined ones of the coarse grid, and any the surface
    // reaches across a face of the complex's border whose points disagree (fan faces and split
    // faces have points the coarse grid did not look at).
    std::unordered_set<std::uint64_t> coarse;
    for (std::uint64_t cell : sorted_cells)
      if (!refined.count(cell)) coarse.insert(cell);
    std::vector<std::uint64_t> grow_from(sorted_refined);
    for (std::uint64_t cell : sorted_cells)
      if (!refined.count(cell)) grow_from.push_back(cell);
    // Each round's cells are looked at in parallel, in chunks whose results are entered in
    // order: the same labels and cells as one serial pass.
    constexpr std::size_t kGrowChunk = 256;
    while (!grow_from.empty()) {
      const std::size_t n_chunks = (grow_from.size() + kGrowChunk - 1) / kGrowChunk;
      const auto chunk_range = [&](std::size_t c) {
        return std::pair<std::size_t, std::size_t>{c * kGrowChunk, std::min(grow_from.size(), (c + 1) * kGrowChunk)};
      };
      std::vector<std::vector<std::uint64_t>> chunk_corners(n_chunks), chunk_centres(n_chunks);
      tbb::parallel_for(std::size_t{0}, n_chunks, [&](std::size_t c) {
        const auto range = chunk_range(c);
        for (std::size_t k = range.first; k < range.second; ++k)
          if (!refined.count(grow_from[k])) cell_points(grow_from[k], ratio, chunk_corners[c], chunk_centres[c]);
      });
      std::vector<std::uint64_t> corners, centres;
      for (std::size_t c = 0; c < n_chunks; ++c) {
        corners.insert(corners.end(), chunk_corners[c].begin(), chunk_corners[c].end());
        centres.insert(centres.end(), chunk_centres[c].begin(), chunk_centres[c].end());
      }
      chunk_corners.clear();
      chunk_centres.clear();
      label_all(std::move(corners), ratio);
      label_all(std::move(centres), ratio / 2);
      // Neighbours across a face whose points disagree, not in the complex before this round.
      std::vector<std::vector<std::uint64_t>> chunk_grown(n_chunks);
      tbb::parallel_for(std::size_t{0}, n_chunks, [&](std::size_t c) {
        const auto range = chunk_range(c);
        std::vector<std::array<std::uint64_t, 3>> face;
        for (std::size_t k = range.first; k < range.second; ++k) {
          const std::uint64_t cell = grow_from[k];
          const auto i = grid.index(cell);
          for (int axis = 0; axis < 3; ++axis)
            for (int side = 0; side < 2; ++side) {
              std::array<std::int64_t, 3> j = i;
              j[static_cast<std::size_t>(axis)] += side ? ratio : -ratio;
              if (!cell_in_grid(j)) continue;
              const std::uint64_t neighbour = grid.key(j[0], j[1], j[2]);
              if (refined.count(neighbour) || coarse.count(neighbour)) continue;
              face.clear();
              face_triangles(side ? neighbour : cell, axis, ratio, face, nullptr);
              int in = 0, count = 0;
              for (const auto& t : face)
                for (std::uint64_t key : t) {
                  in += label.at(key);
                  ++count;
                }
              if (in == 0 || in == count) continue;
              chunk_grown[c].push_back(neighbour);
            }
        }
      });
      std::vector<std::uint64_t> grown;
      for (const std::vector<std::uint64_t>& found : chunk_grown)
        for (std::uint64_t neighbour : found)
          if (coarse.insert(neighbour).second) grown.push_back(neighbour);
      if (static_cast<std::int64_t>(coarse.size() + refined.size()) > options.max_cells)
        throw InvalidInput("the contouring grid needs more than " + std::to_string(options.max_cells) + " cells; choose a larger cell size",
                           "cell_size");
      grow_from = std::move(grown);
    }
    // The complex's tetrahedra, cell by cell: Kuhn's or coned from the cell's centre.
    polygons.clear();
    cell_of.clear();
    std::vector<std::pair<std::uint64_t, std::int64_t>> complex;
    for (std::uint64_t cell : coarse) complex.emplace_back(cell, ratio);
    complex.insert(complex.end(), fine_leaves.begin(), fine_leaves.end());
    std::sort(complex.begin(), complex.end());
    march_cells(complex, [&](std::size_t k, std::uint64_t cell, std::vector<ContourPolygon>& out) { march_leaf(complex[k].first, complex[k].second, cell, out); });
    stats.grid_cells = static_cast<std::int64_t>(complex.size());
    // Crossings of the edges the complex uses; those of earlier complexes' edges are kept.
    cross_new_edges();
  };
  auto build_complex = [&]() {
    // The cells of each level between coarse and unit where the contour bends: split (their
    // polygons and crossings alone are made to find them).
    // Not below crease_width: narrower cells only where the verification asks (adaptation).
    for (std::size_t l = 1; l + 1 < levels; ++l) {
      if (level_size[l + 1] < options.crease_width) break;
      make_complex(level_size[l]);
      for (std::uint64_t cell : bent_cells(level_size[l])) split[l].insert(cell);
    }
    make_complex(0);
    std::vector<int> renumber(edges.size(), -1);
    crossings.clear();
    for (ContourPolygon& polygon : polygons)
      for (int j = 0; j < polygon.count; ++j) {
        int& v = polygon.vertex[static_cast<std::size_t>(j)];
        if (renumber[static_cast<std::size_t>(v)] < 0) {
          renumber[static_cast<std::size_t>(v)] = static_cast<int>(crossings.size());
          crossings.push_back(all_crossings[static_cast<std::size_t>(v)]);
        }
        v = renumber[static_cast<std::size_t>(v)];
      }
  };
  // With adaptive cells, the cells holding edges that the verification finds farther than the
  // tolerance from the boundary (a feature between the cells' corners: a thin fin, a crease the
  // crossings did not show) and their neighbours of the same width are split down to unit
  // cells, and the contour is made again; at most twice.
  const int max_adaptations = ratio > 1 ? 2 : 0;
  std::vector<Eigen::Vector3d> beyond_points;
  double checks_total = 0;
  // Repair rounds and adaptations change a few percent of the faces: each self-intersection
  // test looks only at the pairs that involve a face the last tested mesh did not have.
  SelfIntersectionRecord self_intersection_record;
  // The refinement's splits likewise: most edges of a contour made again have the same two ends.
  SheetRefinementMemory refinement_memory;
  // Splits the cells holding `beyond_points` and their neighbours down to unit cells (graded
  // toward the points where coarse cells are wider than 4 units, below); false if
  // all were unit cells already, or if the adaptation is refused (max_adaptation_growth: then
  // nothing is split and `last_refused` is set).
  // The cells to split are decided against the cells split before this call, not against the
  // neighbours this call adds: `beyond_points` arrive in the order the parallel verification
  // found them, and skipping a point whose cell an earlier point's neighbourhood had just split
  // made the complex (and Fig. 5's output) depend on thread timing.
  bool last_refused = false;
  auto refine_cells_at = [&] {
    last_refused = false;
    // The splits this call adds, taken back if the adaptation is refused.
    std::vector<std::pair<std::size_t, std::uint64_t>> added;
    const auto mark = [&](std::size_t level, std::uint64_t cell) {
      if (split[level].insert(cell).second) added.emplace_back(level, cell);
    };
    // The unit cube holding each point and the width of the leaf around it.
    std::vector<std::pair<LatticeIndex, std::int64_t>> centres;
    for (const Eigen::Vector3d& p : beyond_points) {
      LatticeIndex u{};
      for (std::size_t d = 0; d < 3; ++d)
        u[d] = std::clamp<std::int64_t>(
            static_cast<std::int64_t>(std::floor((p[static_cast<Eigen::Index>(d)] - grid.origin[static_cast<Eigen::Index>(d)]) / grid.h)), 0,
            grid.n[d] - 2);
      // Where the edge lies in unit cells already, refining more would not change it.
      const std::int64_t s = leaf_size(u);
      if (s > 1) centres.emplace_back(u, s);
    }
    // Splits cell j (level l) and its ancestors; with `to_unit`, its descendants down to unit
    // cells as well.
    const auto split_cell = [&](const LatticeIndex& j, std::size_t l, bool to_unit) {
      for (std::size_t a = 0; a < l; ++a) mark(a, index_key(floor_to(j, level_size[a])));
      std::vector<std::pair<std::uint64_t, std::size_t>> todo{{index_key(j), l}};
      while (!todo.empty()) {
        const auto [cell, level] = todo.back();
        todo.pop_back();
        if (level + 1 >= levels) continue;
        mark(level, cell);
        if (!to_unit) continue;
        const std::int64_t child = level_size[level + 1], n = level_size[level] / child;
        for (std::int64_t k = 0; k < n; ++k)
          for (std::int64_t jj = 0; jj < n; ++jj)
            for (std::int64_t ii = 0; ii < n; ++ii) todo.emplace_back(offset_key(cell, ii * child, jj * child, k * child), level + 1);
      }
    };
    // Graded toward the point (decision, 2026-12-07): with coarse cells wider than 4 units (the
    // fine tolerances' automatic ratios) a cell is split one level, with its 26 neighbours of
    // the same width, and so on into the half holding the point, down to unit cells: a full
    // split of 27 coarse cells would be 27 x 32^3 unit cells per point at ratio 32. With the
    // default ratio 4 of 1e-3 the cell and its 26 neighbours are split straight to unit cells, as
    // before (splitting them one level per adaptation needed a second adaptation on Fig. 5).
    const std::int64_t kFullSplitWidth = ratio > 4 ? 1 : 4;
    for (const auto& [u, leaf] : centres) {
      for (std::size_t l = level_of(leaf); l + 1 < levels; ++l) {
        const std::int64_t s = level_size[l];
        const LatticeIndex i = floor_to(u, s);
        const bool to_unit = s <= kFullSplitWidth;
        for (std::int64_t dk = -1; dk <= 1; ++dk)
          for (std::int64_t dj = -1; dj <= 1; ++dj)
            for (std::int64_t di = -1; di <= 1; ++di) {
              const LatticeIndex j{i[0] + s * di, i[1] + s * dj, i[2] + s * dk};
              bool in_grid = true;
              for (std::size_t d = 0; d < 3; ++d) in_grid = in_grid && j[d] >= 0 && j[d] <= grid.n[d] - 1 - s;
              if (in_grid) split_cell(j, l, to_unit);
            }
        if (to_unit) break;
      }
    }
    // Each new split replaces a leaf by eight.
    const double leaves = static_cast<double>(stats.grid_cells) + 7.0 * static_cast<double>(added.size());
    if (!added.empty() &&
        leaves > std::max(options.max_adaptation_growth * static_cast<double>(stats.grid_cells), static_cast<double>(options.max_adaptation_floor))) {
      for (const auto& [level, cell] : added) split[level].erase(cell);
      stats.grid_adaptation_refused = true;
      last_refused = true;
      return false;
    }
    if (!added.empty()) stats.grid_adaptation_refused = false;
    return !added.empty();
  };
  for (int adaptation = 0;; ++adaptation) {
  if (ratio > 1) {
    build_complex();
  } else {
    crossings = all_crossings;
    stats.grid_cells = static_cast<std::int64_t>(cells.size());
  }
  stats.grid_corners = static_cast<std::int64_t>(label.size());
  stats.crossings_on_sheets = stats.crossings_after_bisection = stats.crossings_off_superset = 0;
  stats.crease_repairs = 0;
  out.mesh = TriangleMesh();
  out.extra.clear();
  out.source_vertex.clear();
  stats.grid_corners_inferred = inferred;
  for (const ContourCrossing& x : crossings) {
    stats.crossings_on_sheets += x.on_sheet ? 1 : 0;
    stats.crossings_after_bisection += x.after_bisection ? 1 : 0;
    stats.crossings_off_superset += x.off_superset ? 1 : 0;
  }
  stats.seconds_classify = seconds_since(classify_start) - checks_total;
  beyond_points.clear();

  // The mesh: parameters (and extra) from the sheet, or interpolated in the crossing's superset
  // triangle.
  const auto checks_start = ContourClock::now();
  if (options.progress) options.progress->begin_phase("checks");
  TriangleMesh& result = out.mesh;
  std::vector<int> vertex_part(crossings.size());
  for (std::size_t e = 0; e < crossings.size(); ++e) {
    const ContourCrossing& x = crossings[e];
    const auto& tri = superset.triangles[x.triangle];
    Eigen::Vector3d param = x.parameters;
    double value = x.extra;
    if (!x.on_sheet) {
      param.setZero();
      value = 0;
      for (int j = 0; j < 3; ++j) {
        const auto v = static_cast<std::size_t>(tri[static_cast<std::size_t>(j)]);
        param += x.barycentric[j] * superset.parameters[v];
        if (!extra.empty()) value += x.barycentric[j] * extra[v];
      }
    }
    result.add_vertex(x.position, param);
    if (!extra.empty()) out.extra.push_back(value);
    out.source_vertex.push_back(tri[0]);
    vertex_part[e] = superset.parts[x.triangle];
  }

  // Creases: in a grid cell whose vertices' sheet normals differ by more than the crease angle,
  // the surface bends sharply inside it (extended marching cubes, Kobbelt et al. 2001). When the
  // cell's triangles form one disk, they are replaced by a fan around the point nearest the
  // disk's centre where the vertices' tangent planes meet (the truncated least squares of dual
  // contouring, Ju et al. 2002), clipped to the cell, provided every fan triangle faces the
  // disk's way. The fan keeps the disk's border, so the surface stays closed and oriented.
  const double crease_cos = std::cos(options.crease_angle_degrees * std::numbers::pi / 180);
  const bool snap_creases = options.refinement_tolerance > 0 && sheet_crossing && sheet_crossing_from && !sheet_of_triangle.empty();
  auto sheet_point_of = [&](const ContourCrossing& x) {
    SheetPoint p;
    p.sheet = sheet_of_triangle[x.triangle];
    p.triangle = x.triangle;
    p.parameters << x.parameters, x.extra;
    p.normal = x.normal;
    return p;
  };
  const auto n_crossings = static_cast<int>(crossings.size());
  // Crease fans and flips are made with floating-point positions and local checks only; where
  // the result's self-intersection check (CGAL, exact) finds a pair of faces that a flip or a
  // fan made, the faces are made again without that flip (or without the fans of that cell),
  // a few rounds at most. The plain marching-tetrahedra faces stay closed and oriented.
  const TriangleMesh crossing_vertices = result;
  const std::vector<double> crossing_extra = out.extra;
  const std::vector<int> crossing_source = out.source_vertex;
  const std::vector<int> crossing_part = vertex_part;
  constexpr std::uint64_t kNoFlip = ~std::uint64_t{0};
  std::set<std::uint64_t> unfanned_cells, unflipped_edges;
  // Crossings whose edges are not refined: corners of faces that refinement made intersect.
  std::set<int> unrefined_vertices;
  const std::int64_t max_rounds = 4;
  bool adapted = false;
  // A crease fan worked out for a cell or one of its tetrahedra: the fan's apex (on the crease
  // where snapped), its border loop, and the crossing nearest the apex, whose tags it takes.
  struct FanPlan {
    Eigen::Vector3d apex;
    std::optional<SheetVertex> on_crease;
    std::vector<int> loop;
    int near_vertex = 0;
  };
  // What a cell's faces will be: its disk's fan, each tetrahedron's own fan or plain faces, or
  // its plain faces. Worked out for all cells in parallel (the fans' Newton and membership tests
  // are most of the time), then emitted in cell order, so that the output does not depend on
  // the threads. The plans depend on the cell's crossings and on whether the cell may have
  // fans, so a repair round works out again only the cells whose fans it took away.
  struct TetrahedronPlan {
    std::optional<FanPlan> fan;
    std::vector<std::array<int, 3>> faces;
    bool unsnapped = false;
  };
  struct CellPlan {
    bool made = false;
    bool fans_allowed = true;
    std::optional<FanPlan> fan;
    bool per_tetrahedron = false;
    std::vector<std::array<int, 3>> faces;
    std::vector<TetrahedronPlan> tetrahedra;
    bool unsnapped = false;
  };
  std::vector<std::pair<std::size_t, std::size_t>> cell_polygons;
  for (std::size_t first_polygon = 0; first_polygon < polygons.size();) {
    std::size_t end_polygon = first_polygon;
    while (end_polygon < polygons.size() && polygons[end_polygon].cell == polygons[first_polygon].cell) ++end_polygon;
    cell_polygons.emplace_back(first_polygon, end_polygon);
    first_polygon = end_polygon;
  }
  std::vector<CellPlan> cell_plans(cell_polygons.size());
  for (std::int64_t round = 0;; ++round) {
    result = crossing_vertices;
    out.extra = crossing_extra;
    out.source_vertex = crossing_source;
    vertex_part = crossing_part;
    stats.crease_vertices = 0;
    stats.crease_flips = 0;
    stats.crease_cells_unsnapped = 0;
    // Crease points put on the curve where their two sheets meet (extract/sheet_refinement.h).
    std::unordered_map<int, SheetVertex> crease_sheets;
    std::vector<std::array<int, 3>> faces;
    // Per face: its grid cell, whether a crease fan made it, and the edge a flip replaced.
    std::vector<std::uint64_t> face_cell, face_flip;
    std::vector<char> face_fan;
    std::uint64_t current_cell = 0;
    auto part_of = [&](int v) { return vertex_part[static_cast<std::size_t>(v)]; };
    auto position_of = [&](int v) -> const Eigen::Vector3d& { return result.positions[static_cast<std::size_t>(v)]; };
    // The fan around the crease point of one cell: false (nothing emitted) unless the cell's
    // triangles `local` form one disk and the fan is valid.
    using HalfSpace = std::pair<Eigen::Vector3d, double>;
    auto crease_fan = [&](const std::vector<std::array<int, 3>>& local, const std::vector<int>& corners, const std::vector<HalfSpace>& region,
                          bool must_snap) -> std::optional<FanPlan> {
      // The disk's border: directed edges whose reverse is not in the cell, one loop.
      std::set<std::pair<int, int>> directed;
      for (const auto& t : local)
        for (int j = 0; j < 3; ++j) directed.emplace(t[static_cast<std::size_t>(j)], t[static_cast<std::size_t>((j + 1) % 3)]);
      std::map<int, int> next;
      std::size_t undirected = 0;
      for (const auto& [p, q] : directed) {
        if (!directed.count({q, p})) {
          if (!next.emplace(p, q).second) return std::nullopt;
          ++undirected;
        } else if (p < q) {
          ++undirected;
        }
      }
      if (next.size() < 3) return std::nullopt;
      if (static_cast<std::ptrdiff_t>(corners.size()) - static_cast<std::ptrdiff_t>(undirected) + static_cast<std::ptrdiff_t>(local.size()) != 1)
        return std::nullopt;
      std::vector<int> loop{next.begin()->first};
      while (loop.size() <= next.size()) {
        const auto it = next.find(loop.back());
        if (it == next.end()) return std::nullopt;
        if (it->second == loop.front()) break;
        loop.push_back(it->second);
      }
      if (loop.size() != next.size()) return std::nullopt;
      // The tangent planes' meeting point nearest the centre: a point (three independent normals,
      // a corner) or a line (two, a crease), clipped to the cell.
      Eigen::Vector3d centre = Eigen::Vector3d::Zero();
      for (int v : corners) centre += position_of(v) / static_cast<double>(corners.size());
      Eigen::MatrixX3d planes(static_cast<Eigen::Index>(corners.size()), 3);
      Eigen::VectorXd offsets(static_cast<Eigen::Index>(corners.size()));
      for (std::size_t j = 0; j < corners.size(); ++j) {
        const Eigen::Vector3d& n = crossings[static_cast<std::size_t>(corners[j])].normal;
        planes.row(static_cast<Eigen::Index>(j)) = n.transpose();
        offsets(static_cast<Eigen::Index>(j)) = n.dot(position_of(corners[j]) - centre);
      }
      const Eigen::JacobiSVD<Eigen::MatrixX3d> svd(planes, Eigen::ComputeFullU | Eigen::ComputeFullV);
      const Eigen::Vector3d sigma = svd.singularValues();
      Eigen::Vector3d shift = Eigen::Vector3d::Zero();
      int rank = 0;
      for (int i = 0; i < 3; ++i)
        if (sigma(i) > 0.1 * sigma(0)) {
          shift += svd.matrixV().col(i) * (svd.matrixU().col(i).dot(offsets) / sigma(i));
          ++rank;
        }
      if (rank < 2) return std::nullopt;
      // Clipped to the region n . x <= c (each half-space moved in by `inset`).
      const double inset = 1e-6 * grid.h;
      Eigen::Vector3d apex = centre + shift;
      if (rank == 2) {
        const Eigen::Vector3d direction = svd.matrixV().col(2);
        double s_low = -std::numeric_limits<double>::infinity(), s_high = std::numeric_limits<double>::infinity();
        for (const auto& [n, c] : region) {
          const double slope = n.dot(direction), room = c - inset - n.dot(apex);
          if (std::abs(slope) < 1e-12) {
            if (room <= 0) return std::nullopt;
          } else if (slope > 0) {
            s_high = std::min(s_high, room / slope);
          } else {
            s_low = std::max(s_low, room / slope);
          }
        }
        if (!(s_low <= s_high)) return std::nullopt;
        apex += std::clamp(0.0, s_low, s_high) * direction;
      }
      for (const auto& [n, c] : region)
        if (!(n.dot(apex) <= c)) return std::nullopt;
      // On a crease of two sheets (rank 2) and with the sheets' equations: the point where the
      // sheets meet in the plane through the apex across the crease, if it is in the region.
      std::optional<SheetVertex> on_crease;
      if (rank == 2 && snap_creases) {
        // The pair of crossings whose normals differ most, first among pairs on two sheets, then
        // among pairs on one sheet (two branches of a sheet that crosses itself, Fig. 5's ridge:
        // docs/envelopes.md); the second is tried where the first gives no crease point.
        std::array<std::size_t, 2> first{0, 0}, second{0, 0};
        std::array<double, 2> smallest{2, 2};
        for (std::size_t i = 0; i < corners.size(); ++i)
          for (std::size_t j = 0; j < i; ++j) {
            const ContourCrossing &xi = crossings[static_cast<std::size_t>(corners[i])], &xj = crossings[static_cast<std::size_t>(corners[j])];
            if (!xi.on_sheet || !xj.on_sheet) continue;
            const std::size_t kind = sheet_of_triangle[xi.triangle] == sheet_of_triangle[xj.triangle] ? 1 : 0;
            const double c = std::abs(xi.normal.dot(xj.normal));
            if (c < smallest[kind]) smallest[kind] = c, first[kind] = i, second[kind] = j;
          }
        for (std::size_t kind = 0; kind < 2 && !on_crease; ++kind) {
          if (!(smallest[kind] < crease_cos)) continue;
          SheetVertex v;
          v.on[0] = sheet_point_of(crossings[static_cast<std::size_t>(corners[first[kind]])]);
          v.on[1] = sheet_point_of(crossings[static_cast<std::size_t>(corners[second[kind]])]);
          const Eigen::Vector3d direction = v.on[0].normal.cross(v.on[1].normal);
          CreaseKey key{};
          {
            std::size_t k = 0;
            for (const SheetPoint* p : {&v.on[0], &v.on[1]}) {
              key[k++] = static_cast<double>(p->sheet);
              key[k++] = static_cast<double>(p->triangle);
              for (int i = 0; i < 4; ++i) key[k++] = p->parameters[i] + 0.0;
              for (int i = 0; i < 3; ++i) key[k++] = p->normal[i] + 0.0;
            }
            for (int i = 0; i < 3; ++i) key[k++] = apex[i] + 0.0;
            for (int i = 0; i < 3; ++i) key[k++] = direction[i] + 0.0;
            key[k++] = grid.h;
          }
          std::optional<Eigen::Vector3d> x;
          if (const auto it = remembered_creases.find(key); it != remembered_creases.end()) {
            x = it->second.point;
            v.on[0] = it->second.a;
            v.on[1] = it->second.b;
          } else {
            x = sheet_crease_point(sheet_crossing_from, v.on[0], v.on[1], apex, direction, grid.h);
            remembered_creases.emplace(key, CreaseAnswer{x, v.on[0], v.on[1]});
          }
          // A crease only where the sheets meet at the crease angle or more there: two sheets
          // of one smooth surface (a seam, a coarse cell's curvature) meet tangentially, where
          // their meeting point is ill-conditioned and not needed.
          bool in_region = x.has_value() && std::abs(v.on[0].normal.normalized().dot(v.on[1].normal.normalized())) < crease_cos;
          for (const auto& [n, c] : region) in_region = in_region && n.dot(*x) <= c + inset;
          if (in_region) {
            apex = *x;
            on_crease = v;
          }
        }
      }
      // With refinement, a fan only around a point on a real crease: where the crossings' normals
      // differ because a coarse cell spans a curved part of one smooth surface, the tangent planes
      // meet off the surface and the plain triangles, refined, are better. The fine cells of
      // adaptive contouring are as fine as the uniform grid's, whose fans need no snapping.
      if (must_snap && !on_crease) return std::nullopt;
      // Each fan triangle faces the way of the disk (area-weighted) or of the cell's triangle it
      // replaces along the border (a sliver standing on the crease may face sideways): a fold of
      // the fan would be a self-intersection.
      Eigen::Vector3d disk_normal = Eigen::Vector3d::Zero();
      for (const auto& t : local) disk_normal += (position_of(t[1]) - position_of(t[0])).cross(position_of(t[2]) - position_of(t[0]));
      for (std::size_t j = 0; j < loop.size(); ++j) {
        const int p = loop[j], q = loop[(j + 1) % loop.size()];
        const Eigen::Vector3d fan_normal = (position_of(p) - apex).cross(position_of(q) - apex);
        if (fan_normal.dot(disk_normal) > 0) continue;
        for (const auto& t : local)
          for (int i = 0; i < 3; ++i)
            if (t[static_cast<std::size_t>(i)] == p && t[static_cast<std::size_t>((i + 1) % 3)] == q &&
                fan_normal.dot((position_of(t[1]) - position_of(t[0])).cross(position_of(t[2]) - position_of(t[0]))) <= 0)
              return std::nullopt;
      }
      // The crease point must lie on the boundary to half the superset's error: just outside it
      // (along the disk's outward normal) is outside S and just inside it inside. A sheet's normal
      // that does not belong to the boundary there (an interior sheet meeting it) fails this.
      if (disk_normal.norm() > 0) {
        const Eigen::Vector3d step = 0.25 * reach * disk_normal.normalized();
        auto in = [&](const Eigen::Vector3d& x) {
          const std::optional<bool> answer = checked_inside(x);
          return !answer || *answer;
        };
        if (in(apex + step) || !in(apex - step)) return std::nullopt;
      }
      std::size_t nearest = 0;
      for (std::size_t j = 1; j < corners.size(); ++j)
        if ((position_of(corners[j]) - apex).squaredNorm() < (position_of(corners[nearest]) - apex).squaredNorm()) nearest = j;
      FanPlan plan;
      plan.apex = apex;
      plan.on_crease = on_crease;
      plan.loop = std::move(loop);
      plan.near_vertex = corners[nearest];
      return plan;
    };
    // Emits a fan: its apex as a new vertex, its triangles as faces.
    auto emit_fan = [&](const FanPlan& plan) {
      const int near_vertex = plan.near_vertex;
      const int v = static_cast<int>(result.num_vertices());
      if (plan.on_crease) crease_sheets.emplace(v, *plan.on_crease);
      result.add_vertex(plan.apex, plan.on_crease ? Eigen::Vector3d(plan.on_crease->on[0].parameters.head<3>())
                                                  : result.parameters[static_cast<std::size_t>(near_vertex)]);
      if (!extra.empty()) out.extra.push_back(out.extra[static_cast<std::size_t>(near_vertex)]);
      out.source_vertex.push_back(out.source_vertex[static_cast<std::size_t>(near_vertex)]);
      vertex_part.push_back(vertex_part[static_cast<std::size_t>(near_vertex)]);
      face_fan.resize(faces.size(), 0);
      const std::vector<int>& loop = plan.loop;
      for (std::size_t j = 0; j < loop.size(); ++j) {
        faces.push_back({v, loop[j], loop[(j + 1) % loop.size()]});
        face_fan.push_back(1);
      }
      ++stats.crease_vertices;
      if (!plan.on_crease) ++stats.crease_cells_unsnapped;
    };
    // A marching-tetrahedra polygon as triangles, a quadrilateral split along its shorter diagonal.
    auto polygon_triangles = [&](const ContourPolygon& polygon, std::vector<std::array<int, 3>>& out) {
      const auto count = static_cast<std::size_t>(polygon.count);
      std::size_t first = 0;
      if (count == 4 && (position_of(polygon.vertex[1]) - position_of(polygon.vertex[3])).squaredNorm() <
                            (position_of(polygon.vertex[0]) - position_of(polygon.vertex[2])).squaredNorm())
        first = 1;
      for (std::size_t j = 1; j + 1 < count; ++j)
        out.push_back({polygon.vertex[first], polygon.vertex[(first + j) % count], polygon.vertex[(first + j + 1) % count]});
    };
    // Whether the crossings `corners` (sorted) all lie on sheets with normals, starting from
    // `sharp`, and the smallest |cos| between their normals (as far as it was looked at).
    auto normals_spread = [&](const std::vector<int>& corners, bool sharp) {
      double smallest_cos = 1;
      for (std::size_t j = 0; sharp && j < corners.size(); ++j) {
        const ContourCrossing& xj = crossings[static_cast<std::size_t>(corners[j])];
        if (!xj.on_sheet || xj.normal.isZero()) sharp = false;
        for (std::size_t i = 0; sharp && i < j; ++i)
          smallest_cos = std::min(smallest_cos, std::abs(xj.normal.dot(crossings[static_cast<std::size_t>(corners[i])].normal)));
      }
      return std::pair<bool, double>(sharp, smallest_cos);
    };
    auto plan_cell = [&](std::size_t g) {
      CellPlan plan;
      plan.made = true;
      const std::size_t cell_first = cell_polygons[g].first, cell_end = cell_polygons[g].second;
      std::vector<std::array<int, 3>> local;
      std::vector<int> corners;
      for (std::size_t q = cell_first; q < cell_end; ++q) {
        const ContourPolygon& polygon = polygons[q];
        polygon_triangles(polygon, local);
        corners.insert(corners.end(), polygon.vertex.begin(), polygon.vertex.begin() + polygon.count);
      }
      const std::uint64_t cell = polygons[cell_first].cell;
      std::sort(corners.begin(), corners.end());
      corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
      auto [crease, smallest_cos] = normals_spread(corners, sheet_crossing && options.crease_angle_degrees > 0 && corners.size() >= 3);
      const bool fans_allowed = !unfanned_cells.count(cell);
      plan.fans_allowed = fans_allowed;
      crease = crease && smallest_cos < crease_cos && fans_allowed;
      const Eigen::Vector3d low = grid.point(cell_of[cell].low);
      const double width = static_cast<double>(cell_of[cell].size) * grid.h;
      if (crease) {
        std::vector<HalfSpace> box;
        for (int d = 0; d < 3; ++d) {
          const Eigen::Vector3d e = Eigen::Vector3d::Unit(d);
          box.emplace_back(e, low(d) + width);
          box.emplace_back(-e, -low(d));
        }
        plan.fan = crease_fan(local, corners, box, snap_creases && (ratio == 1 || cell_of[cell].size > 1));
        if (plan.fan) return plan;
      }
      if (!(sheet_crossing && options.crease_angle_degrees > 0 && smallest_cos < crease_cos) || !fans_allowed) {
        plan.unsnapped = sheet_crossing && options.crease_angle_degrees > 0 && smallest_cos < crease_cos;
        plan.faces = std::move(local);
        return plan;
      }
      // The cell's triangles are no disk or its fan folds: each tetrahedron's polygon alone.
      plan.per_tetrahedron = true;
      for (std::size_t q = cell_first; q < cell_end; ++q) {
        TetrahedronPlan& own_plan = plan.tetrahedra.emplace_back();
        const ContourPolygon& polygon = polygons[q];
        std::vector<std::array<int, 3>> own;
        polygon_triangles(polygon, own);
        std::vector<int> own_corners(polygon.vertex.begin(), polygon.vertex.begin() + polygon.count);
        std::sort(own_corners.begin(), own_corners.end());
        const auto [sharp, own_cos] = normals_spread(own_corners, true);
        if (sharp && own_cos < crease_cos) {
          // The tetrahedron's four faces, outward.
          std::array<Eigen::Vector3d, 4> corner;
          for (int i = 0; i < 4; ++i) corner[static_cast<std::size_t>(i)] = grid.point(polygon.tetrahedron[static_cast<std::size_t>(i)]);
          std::vector<HalfSpace> faces_of_tet;
          for (int i = 0; i < 4; ++i) {
            const Eigen::Vector3d& p0 = corner[static_cast<std::size_t>((i + 1) % 4)];
            Eigen::Vector3d n = (corner[static_cast<std::size_t>((i + 2) % 4)] - p0).cross(corner[static_cast<std::size_t>((i + 3) % 4)] - p0);
            if (n.dot(corner[static_cast<std::size_t>(i)] - p0) > 0) n = -n;
            n.normalize();
            faces_of_tet.emplace_back(n, n.dot(p0));
          }
          own_plan.fan = crease_fan(own, own_corners, faces_of_tet, snap_creases && (ratio == 1 || cell_of[cell].size > 1));
          if (own_plan.fan) continue;
          own_plan.unsnapped = true;
        }
        own_plan.faces = std::move(own);
      }
      return plan;
    };
    tbb::parallel_for(std::size_t{0}, cell_polygons.size(), [&](std::size_t g) {
      const CellPlan& plan = cell_plans[g];
      if (!plan.made || plan.fans_allowed != !unfanned_cells.count(polygons[cell_polygons[g].first].cell)) cell_plans[g] = plan_cell(g);
    });
    for (std::size_t g = 0; g < cell_polygons.size(); ++g) {
      face_cell.resize(faces.size(), current_cell);
      current_cell = polygons[cell_polygons[g].first].cell;
      const CellPlan& plan = cell_plans[g];
      if (plan.fan) {
        emit_fan(*plan.fan);
        continue;
      }
      if (!plan.per_tetrahedron) {
        if (plan.unsnapped) ++stats.crease_cells_unsnapped;
        faces.insert(faces.end(), plan.faces.begin(), plan.faces.end());
        continue;
      }
      for (const TetrahedronPlan& own : plan.tetrahedra) {
        if (own.fan) {
          emit_fan(*own.fan);
          continue;
        }
        if (own.unsnapped) ++stats.crease_cells_unsnapped;
        faces.insert(faces.end(), own.faces.begin(), own.faces.end());
      }
    }

    // Edge flips across creases (extended marching cubes): an edge between two crossings on
    // different sheets whose two triangles are fans around crease vertices x1, x2 becomes the
    // edge x1 x2, so that the crease runs from crease vertex to crease vertex instead of being
    // cut at every tetrahedron face. Only where both new triangles face the old ones' way and
    // x1 x2 is not an edge yet.
    face_cell.resize(faces.size(), current_cell);
    face_fan.resize(faces.size(), 0);
    face_flip.assign(faces.size(), kNoFlip);
    if (stats.crease_vertices > 0) {
      auto edge_key = [](int p, int q) { return (static_cast<std::uint64_t>(std::min(p, q)) << 32) | static_cast<std::uint32_t>(std::max(p, q)); };
      // Only fan faces take part: a flip joins two fans' apexes across an edge of both, and the
      // edges it looks up or replaces end at an apex, which no other face has (the surface is a
      // 2-manifold, so an edge of two fan faces has no third face). Mapping every edge of the
      // 200,000 faces took most of this step's time on Fig. 5.
      std::unordered_map<std::uint64_t, std::array<int, 2>> edge_faces;
      for (std::size_t f = 0; f < faces.size(); ++f)
        for (int j = 0; j < 3 && face_fan[f]; ++j) {
          auto [it, fresh] = edge_faces.try_emplace(edge_key(faces[f][static_cast<std::size_t>(j)], faces[f][static_cast<std::size_t>((j + 1) % 3)]),
                                                    std::array<int, 2>{static_cast<int>(f), -1});
          if (!fresh) it->second[1] = it->second[1] < 0 ? static_cast<int>(f) : -2;
        }
      auto normal_of = [&](const std::array<int, 3>& f) {
        const Eigen::Vector3d& p = result.positions[static_cast<std::size_t>(f[0])];
        return Eigen::Vector3d((result.positions[static_cast<std::size_t>(f[1])] - p).cross(result.positions[static_cast<std::size_t>(f[2])] - p));
      };
      auto replace_face = [&](int p, int q, int from, int to) {
        auto& pair = edge_faces.at(edge_key(p, q));
        for (int& f : pair)
          if (f == from) f = to;
      };
      std::vector<std::uint64_t> keys;
      for (const auto& [k, f] : edge_faces)
        if (f[1] >= 0) keys.push_back(k);
      std::sort(keys.begin(), keys.end());
      for (std::uint64_t k : keys) {
        const auto u0 = static_cast<int>(k >> 32), v0 = static_cast<int>(k & 0xffffffffu);
        if (u0 >= n_crossings || v0 >= n_crossings || unflipped_edges.count(k)) continue;
        const std::array<int, 2> pair = edge_faces.at(k);
        if (pair[1] < 0) continue;
        const ContourCrossing &xu = crossings[static_cast<std::size_t>(u0)], &xv = crossings[static_cast<std::size_t>(v0)];
        if (xu.normal.isZero() || xv.normal.isZero() || std::abs(xu.normal.dot(xv.normal)) >= crease_cos) continue;
        // f1 = (x1, u, v), f2 = (x2, v, u) after rotation.
        auto rotate_to = [&](int f, int first) {
          std::array<int, 3> t = faces[static_cast<std::size_t>(f)];
          while (t[1] != first) std::rotate(t.begin(), t.begin() + 1, t.end());
          return t;
        };
        const int f1 = pair[0], f2 = pair[1];
        std::array<int, 3> t1 = faces[static_cast<std::size_t>(f1)], t2 = faces[static_cast<std::size_t>(f2)];
        // Orient: t1 holds u -> v, t2 holds v -> u.
        int u = u0, v = v0;
        auto has_directed = [](const std::array<int, 3>& t, int p, int q) {
          for (int j = 0; j < 3; ++j)
            if (t[static_cast<std::size_t>(j)] == p && t[static_cast<std::size_t>((j + 1) % 3)] == q) return true;
          return false;
        };
        if (!has_directed(t1, u, v)) std::swap(u, v);
        if (!has_directed(t1, u, v) || !has_directed(t2, v, u)) continue;
        t1 = rotate_to(f1, u);
        t2 = rotate_to(f2, v);
        const int x1 = t1[0], x2 = t2[0];
        if (x1 < n_crossings || x2 < n_crossings || x1 == x2 || edge_faces.count(edge_key(x1, x2))) continue;
        const std::array<int, 3> n1{x1, u, x2}, n2{x1, x2, v};
        // The quadrilateral's way (area-weighted: one of the old triangles is often a sliver
        // standing on the crease).
        const Eigen::Vector3d old_normal = normal_of(t1) + normal_of(t2);
        const Eigen::Vector3d m1 = normal_of(n1), m2 = normal_of(n2);
        if (m1.dot(old_normal) <= 0 || m2.dot(old_normal) <= 0) continue;
        faces[static_cast<std::size_t>(f1)] = n1;
        faces[static_cast<std::size_t>(f2)] = n2;
        face_flip[static_cast<std::size_t>(f1)] = face_flip[static_cast<std::size_t>(f2)] = k;
        replace_face(u, x2, f2, f1);
        replace_face(v, x1, f1, f2);
        edge_faces.erase(k);
        edge_faces.emplace(edge_key(x1, x2), std::array<int, 2>{f1, f2});
        ++stats.crease_flips;
      }
    }
    // A face's part: that of its crossings (crease vertices lie on two sheets and do not vote);
    // where they differ, the sheet whose normal is nearest the face's.
    for (const auto& f : faces) {
      const Eigen::Vector3d& p = result.positions[static_cast<std::size_t>(f[0])];
      const Eigen::Vector3d normal = (result.positions[static_cast<std::size_t>(f[1])] - p).cross(result.positions[static_cast<std::size_t>(f[2])] - p);
      int part = -1;
      double best = -1;
      for (int v : f) {
        if (v >= n_crossings) continue;
        const ContourCrossing& x = crossings[static_cast<std::size_t>(v)];
        const double alignment = x.normal.isZero() || !(normal.norm() > 0) ? 0 : std::abs(x.normal.dot(normal.normalized()));
        if (part < 0 || alignment > best) {
          part = part_of(v);
          best = alignment;
        }
      }
      result.add_triangle(f[0], f[1], f[2], part < 0 ? part_of(f[0]) : part);
    }
    // Refinement toward the sheets: the grid gives the topology and the creases, the sheets'
    // equations the accuracy of the smooth parts (extract/sheet_refinement.h).
    std::vector<std::size_t> face_origin;
    const bool refine = snap_creases;
    if (refine) {
      const auto refine_start = ContourClock::now();
      std::vector<SheetVertex> sheet_vertices(result.num_vertices());
      for (std::size_t v = 0; v < sheet_vertices.size(); ++v) {
        SheetVertex& sv = sheet_vertices[v];
        if (v >= crossings.size()) {
          if (const auto it = crease_sheets.find(static_cast<int>(v)); it != crease_sheets.end()) sv = it->second;
          sv.source = out.source_vertex[v];
          continue;
        }
        sv.source = out.source_vertex[v];
        sv.frozen = unrefined_vertices.count(static_cast<int>(v)) > 0;
        const ContourCrossing& x = crossings[v];
        if (!x.on_sheet || x.normal.isZero()) continue;
        sv.on[0] = sheet_point_of(x);
      }
      SheetRefinementOptions refinement;
      refinement.tolerance = options.refinement_tolerance * diagonal;
      refinement.shortest_edge = 1e-3 * grid.h;
      refinement.inside = checked_inside;
      refinement.check_distance = 0.25 * reach;
      refinement.memory = &refinement_memory;
      if (options.crease_angle_degrees > 0) refinement.branch_angle_degrees = std::min(options.crease_angle_degrees, 90.0);
      const std::size_t before = sheet_vertices.size();
      const SheetRefinementStats r = refine_to_sheets(result, sheet_vertices, sheet_crossing_from, refinement, &face_origin);
      for (std::size_t v = before; v < sheet_vertices.size(); ++v) {
        if (!extra.empty()) out.extra.push_back(sheet_vertices[v].on[0].parameters[3]);
        out.source_vertex.push_back(sheet_vertices[v].source);
      }
      stats.refinement_edges_verified = 0;
      stats.refinement_edges_beyond_tolerance = 0;
      stats.refinement_tolerance = refinement.tolerance;
      stats.refinement_rounds = r.rounds;
      stats.refinement_splits = r.split_edges;
      stats.refinement_failed_edges = r.failed_edges;
      stats.refinement_unresolved_edges = r.unresolved_edges;
      stats.refinement_edges_above_tolerance = r.edges_above_tolerance;
      stats.refinement_largest_remaining = r.largest_remaining_distance;
      if (options.verification_distance > 0 && !r.unverified_edges.empty()) {
        // Outward normals of the unverified edges: the sum of their faces' (the mesh is
        // outward-oriented).
        std::unordered_map<std::uint64_t, Eigen::Vector3d> edge_normal;
        for (const auto& [p, q] : r.unverified_edges)
          edge_normal.emplace((static_cast<std::uint64_t>(p) << 32) | static_cast<std::uint32_t>(q), Eigen::Vector3d::Zero());
        for (const auto& t : result.triangles) {
          const Eigen::Vector3d& a = result.positions[static_cast<std::size_t>(t[0])];
          const Eigen::Vector3d n =
              (result.positions[static_cast<std::size_t>(t[1])] - a).cross(result.positions[static_cast<std::size_t>(t[2])] - a);
          for (int j = 0; j < 3; ++j) {
            const int p = std::min(t[static_cast<std::size_t>(j)], t[static_cast<std::size_t>((j + 1) % 3)]);
            const int q = std::max(t[static_cast<std::size_t>(j)], t[static_cast<std::size_t>((j + 1) % 3)]);
            const auto it = edge_normal.find((static_cast<std::uint64_t>(p) << 32) | static_cast<std::uint32_t>(q));
            if (it != edge_normal.end()) it->second += n;
          }
        }
        std::vector<std::pair<std::uint64_t, Eigen::Vector3d>> checks(edge_normal.begin(), edge_normal.end());
        std::atomic<std::int64_t> beyond{0};
        beyond_points.clear();
        std::mutex beyond_mutex;
        const double distance = options.verification_distance * diagonal;
        tbb::parallel_for(std::size_t{0}, checks.size(), [&](std::size_t i) {
          const auto& [key, normal] = checks[i];
          const Eigen::Vector3d middle = 0.5 * (result.positions[static_cast<std::size_t>(key >> 32)] +
                                                result.positions[static_cast<std::size_t>(key & 0xffffffffu)]);
          if (!(normal.norm() > 0)) {
            ++beyond;
            return;
          }
          const Eigen::Vector3d step = distance * normal.normalized();
          const std::optional<bool> out = checked_inside(middle + step), in = checked_inside(middle - step);
          if (!out || !in || *out || !*in) {
            ++beyond;
            const std::lock_guard<std::mutex> lock(beyond_mutex);
            beyond_points.push_back(middle);
          }
        });
        stats.refinement_edges_verified = static_cast<std::int64_t>(checks.size());
        stats.refinement_edges_beyond_tolerance = beyond;
      }
      stats.seconds_sheet_refinement = seconds_since(refine_start);
    }
    // Crossings inside a cell's disk that a crease fan replaced are used by no face: dropped.
    std::vector<int> renumber(result.num_vertices(), -1);
    for (const auto& t : result.triangles)
      for (int v : t) renumber[static_cast<std::size_t>(v)] = 0;
    int used = 0;
    for (std::size_t v = 0; v < renumber.size(); ++v)
      if (renumber[v] == 0) {
        renumber[v] = used;
        const auto to = static_cast<std::size_t>(used++);
        result.positions[to] = result.positions[v];
        result.parameters[to] = result.parameters[v];
        if (!out.extra.empty()) out.extra[to] = out.extra[v];
        out.source_vertex[to] = out.source_vertex[v];
      }
    if (used < static_cast<int>(renumber.size())) {
      result.positions.resize(static_cast<std::size_t>(used));
      result.parameters.resize(static_cast<std::size_t>(used));
      if (!out.extra.empty()) out.extra.resize(static_cast<std::size_t>(used));
      out.source_vertex.resize(static_cast<std::size_t>(used));
      for (auto& t : result.triangles)
        for (int& v : t) v = renumber[static_cast<std::size_t>(v)];
    }
    // Where a round's verification asks for finer cells, the contour is made again at once: the
    // self-intersection check and the repairs still to come would be undone. (A repair round can
    // be the first to ask: a fan it took away can leave a chord the coarse cell does not hold.)
    if (adaptation < max_adaptations && !beyond_points.empty() && refine_cells_at()) {
      adapted = true;
      break;
    }
    std::vector<std::pair<std::size_t, std::size_t>> intersecting;
    measure_trimmed_boundary(result, stats, &intersecting, &self_intersection_record);
    if (intersecting.empty() || round + 1 >= max_rounds) break;
    // Undo the flips that made a face of an intersecting pair; where neither face is flipped,
    // drop the fans of the cells of the fan faces among them.
    bool changed = false;
    std::vector<int> children(refine ? faces.size() : 0, 0);
    if (refine)
      for (const std::size_t o : face_origin) ++children[o];
    for (auto [f, g] : intersecting) {
      if (refine) {
        // Faces refinement made (their face before it was split): no refinement at its corners;
        // the fans and flips of their faces stay unless freezing changes nothing.
        bool frozen = false;
        for (const std::size_t h : {f, g}) {
          const auto& parent = faces[face_origin[h]];
          if (children[face_origin[h]] > 1)
            for (int v : parent)
              if (v < n_crossings) frozen = unrefined_vertices.insert(v).second || frozen;
        }
        changed = changed || frozen;
        if (frozen) continue;
        f = face_origin[f];
        g = face_origin[g];
      }
      const bool flipped = face_flip[f] != kNoFlip || face_flip[g] != kNoFlip;
      for (const std::size_t h : {f, g}) {
        if (flipped) {
          if (face_flip[h] != kNoFlip) changed = unflipped_edges.insert(face_flip[h]).second || changed;
        } else if (face_fan[h]) {
          changed = unfanned_cells.insert(face_cell[h]).second || changed;
        }
      }
    }
    if (!changed) break;
    ++stats.crease_repairs;
  }
  stats.seconds_checks = seconds_since(checks_start);
  checks_total += stats.seconds_checks;
  if (!adapted && (adaptation >= max_adaptations || beyond_points.empty() || last_refused || !refine_cells_at())) break;
  ++stats.grid_adaptations;
  }
  stats.seconds_checks = checks_total;
  stats.membership_queries = queries;
  stats.membership_queries_remembered = remembered_queries;
  if (options.progress) options.progress->end_phase();
  return out;
}

}  // namespace volspline
