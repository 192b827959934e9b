#include "volspline/mesh/self_intersections.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <numeric>
#include <unordered_map>
#include <unordered_set>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/box_intersection_d.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "volspline/core/bucket_sort.h"
#include "volspline/core/exact_hash.h"
#include "volspline/mesh/mesh_checks.h"

namespace volspline {

// Not anonymous: SelfIntersectionRecord::State holds these types.
namespace self_intersections_detail {

namespace PMP = CGAL::Polygon_mesh_processing;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using FaceIndex = Mesh::Face_index;

// + 0.0 makes -0 and +0 one key.
std::array<double, 3> position_key(const Eigen::Vector3d& p) { return {p.x() + 0.0, p.y() + 0.0, p.z() + 0.0}; }

// Vertex numbers below 2^21 packed into one key per triangle, smallest first (whether two
// triangles intersect does not depend on the order or the orientation of their corners).
constexpr std::size_t kPackedVertices = std::size_t{1} << 21;

// Meshes of at least this many triangles are tested in slabs in parallel.
constexpr std::size_t kSlabbedTest = 20000;

std::uint64_t packed_triangle(std::array<std::uint64_t, 3> v) {
  std::sort(v.begin(), v.end());
  return (v[0] << 42) | (v[1] << 21) | v[2];
}

}  // namespace self_intersections_detail

struct SelfIntersectionRecord::State {
  // Whether the rest may be used: filled from a closed, oriented 2-manifold whose vertices all
  // have distinct positions, fewer than 2^21 of them.
  bool valid = false;
  // The earlier mesh's vertices by position, its triangles by their packed vertex numbers, and
  // its intersecting pairs.
  std::unordered_map<std::array<double, 3>, std::uint32_t, ExactDoublesHash> vertex_at;
  std::vector<std::uint64_t> triangles;  // sorted
  std::vector<std::pair<std::uint64_t, std::uint64_t>> pairs;
  std::size_t reused = 0;
  std::size_t tested = 0;
};

SelfIntersectionRecord::SelfIntersectionRecord() : state_(std::make_unique<State>()) {}
SelfIntersectionRecord::~SelfIntersectionRecord() = default;
SelfIntersectionRecord::SelfIntersectionRecord(SelfIntersectionRecord&&) noexcept = default;
SelfIntersectionRecord& SelfIntersectionRecord::operator=(SelfIntersectionRecord&&) noexcept = default;
std::size_t SelfIntersectionRecord::reused_triangles() const { return state_ ? state_->reused : 0; }
std::size_t SelfIntersectionRecord::tested_triangles() const { return state_ ? state_->tested : 0; }

std::vector<std::pair<std::size_t, std::size_t>> self_intersecting_triangles(const TriangleMesh& mesh, SelfIntersectionRecord* record) {
  using namespace self_intersections_detail;
  validate_mesh(mesh);
  if (record && !record->state_) record->state_ = std::make_unique<SelfIntersectionRecord::State>();  // moved from
  const std::size_t n = mesh.num_triangles();
  std::vector<std::pair<std::size_t, std::size_t>> result;
  if (n == 0) {
    if (record) *record->state_ = SelfIntersectionRecord::State{};
    return result;
  }
  // A closed, oriented 2-manifold is a polygon mesh as it is; other soups are oriented first
  // (which splits non-manifold vertices, and reverses polygons but never reorders them, so the
  // mesh's faces keep the triangles' indices).
  const bool manifold = edge_statistics(mesh).closed_and_oriented() && nonmanifold_vertices(mesh) == 0;
  auto point_of = [&](int v) {
    const Eigen::Vector3d& p = mesh.positions[static_cast<std::size_t>(v)];
    return Point(p.x(), p.y(), p.z());
  };
  // The triangles `faces` (all of them, in order, for a full test) as a CGAL mesh whose face i is
  // faces[i], its vertices renumbered in order of appearance; `polygon_mesh`: known to be a
  // closed, oriented 2-manifold already.
  auto cgal_mesh = [&](const std::vector<std::size_t>& faces, bool polygon_mesh, Mesh& out) {
    std::vector<std::uint32_t> number(mesh.num_vertices(), std::numeric_limits<std::uint32_t>::max());
    std::vector<Point> points;
    std::vector<std::array<std::size_t, 3>> polygons(faces.size());
    for (std::size_t i = 0; i < faces.size(); ++i)
      for (std::size_t j = 0; j < 3; ++j) {
        const int v = mesh.triangles[faces[i]][j];
        std::uint32_t& k = number[static_cast<std::size_t>(v)];
        if (k == std::numeric_limits<std::uint32_t>::max()) {
          k = static_cast<std::uint32_t>(points.size());
          points.push_back(point_of(v));
        }
        polygons[i][j] = k;
      }
    if (!polygon_mesh && !PMP::is_polygon_soup_a_polygon_mesh(polygons)) PMP::orient_polygon_soup(points, polygons);
    PMP::polygon_soup_to_polygon_mesh(points, polygons, out);
  };

  // The pairs among the triangles `range` (sorted) of a closed, oriented 2-manifold that
  // intersect, as CGAL finds them in a mesh of those triangles and every triangle at one of
  // their corners: a pair's test depends on its corners and on which corners and edges the two
  // share, and with each corner's whole umbrella present the corners stay manifold, one vertex
  // each (only the outer ring's vertices may be split).
  auto pairs_among = [&](const std::vector<std::size_t>& range) {
    std::vector<char> corner(mesh.num_vertices(), 0), in_range(n, 0);
    for (const std::size_t t : range) {
      in_range[t] = 1;
      for (const int v : mesh.triangles[t]) corner[static_cast<std::size_t>(v)] = 1;
    }
    std::vector<std::size_t> faces;
    std::vector<FaceIndex> sub_range;
    for (std::size_t t = 0; t < n; ++t) {
      const auto& tri = mesh.triangles[t];
      if (!corner[static_cast<std::size_t>(tri[0])] && !corner[static_cast<std::size_t>(tri[1])] && !corner[static_cast<std::size_t>(tri[2])])
        continue;
      if (in_range[t]) sub_range.emplace_back(static_cast<Mesh::size_type>(faces.size()));
      faces.push_back(t);
    }
    Mesh check;
    cgal_mesh(faces, false, check);
    std::vector<std::pair<FaceIndex, FaceIndex>> sub_found, found_here;
    PMP::self_intersections<CGAL::Parallel_if_available_tag>(sub_range, check, std::back_inserter(sub_found));
    for (const auto& [f, g] : sub_found)
      found_here.emplace_back(static_cast<Mesh::size_type>(faces[static_cast<std::size_t>(f)]), static_cast<Mesh::size_type>(faces[static_cast<std::size_t>(g)]));
    return found_here;
  };

  SelfIntersectionRecord::State* state = record ? record->state_.get() : nullptr;
  // This mesh's vertices by position (for the next test), and which of them the recorded mesh
  // had: none if two share a position.
  std::unordered_map<std::array<double, 3>, std::uint32_t, ExactDoublesHash> vertex_at;
  bool comparable = state && manifold && mesh.num_vertices() < kPackedVertices;
  if (comparable) {
    vertex_at.reserve(mesh.num_vertices());
    for (std::size_t v = 0; v < mesh.num_vertices() && comparable; ++v)
      comparable = vertex_at.emplace(position_key(mesh.positions[v]), static_cast<std::uint32_t>(v)).second;
  }
  std::vector<std::pair<FaceIndex, FaceIndex>> found;
  if (comparable && state->valid) {
    // Each triangle's key in the recorded mesh's numbering; a corner it did not have makes the
    // triangle new.
    constexpr std::uint64_t kNew = ~std::uint64_t{0};
    // (Lookups only, each writing its own element: in parallel, the same answers.)
    std::vector<std::uint32_t> earlier(mesh.num_vertices(), std::numeric_limits<std::uint32_t>::max());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mesh.num_vertices(), 4096), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t v = r.begin(); v != r.end(); ++v)
        if (const auto it = state->vertex_at.find(position_key(mesh.positions[v])); it != state->vertex_at.end()) earlier[v] = it->second;
    });
    std::vector<std::uint64_t> key(n, kNew);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t t = r.begin(); t != r.end(); ++t) {
        std::array<std::uint64_t, 3> v{};
        bool known = true;
        for (std::size_t j = 0; j < 3; ++j) {
          const std::uint32_t e = earlier[static_cast<std::size_t>(mesh.triangles[t][j])];
          known = known && e != std::numeric_limits<std::uint32_t>::max();
          v[j] = e;
        }
        if (!known) continue;
        const std::uint64_t k = packed_triangle(v);
        if (std::binary_search(state->triangles.begin(), state->triangles.end(), k)) key[t] = k;
      }
    });
    // The recorded pairs' triangles, found where they still are.
    std::unordered_map<std::uint64_t, std::size_t> index;
    for (const auto& [a, b] : state->pairs) {
      index.emplace(a, n);
      index.emplace(b, n);
    }
    if (!index.empty())
      for (std::size_t t = 0; t < n; ++t)
        if (key[t] != kNew)
          if (const auto it = index.find(key[t]); it != index.end()) it->second = t;
    // Pairs of triangles both in the earlier mesh: as found then.
    for (const auto& [a, b] : state->pairs) {
      const std::size_t i = index.at(a), j = index.at(b);
      if (i < n && j < n) result.emplace_back(std::min(i, j), std::max(i, j));
    }
    // Pairs with a new triangle: both lie among the new triangles and those whose (closed)
    // boxes meet a new one's. The boxes that may meet one are found first with a hash of lattice
    // cells as large as the largest new box (two closed boxes that meet share a point, whose
    // cell both boxes cover), so that CGAL's box intersection sorts a few thousand boxes rather
    // than all of them.
    using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::size_t>;
    auto box_of = [&](std::size_t t) {
      const auto& tri = mesh.triangles[t];
      return Box(point_of(tri[0]).bbox() + point_of(tri[1]).bbox() + point_of(tri[2]).bbox(), t);
    };
    std::vector<Box> fresh, near;
    for (std::size_t t = 0; t < n; ++t)
      if (key[t] == kNew) fresh.push_back(box_of(t));
    std::vector<char> tested(n, 0);
    if (!fresh.empty()) {
      double cell = 0;
      for (const Box& b : fresh)
        for (int d = 0; d < 3; ++d) cell = std::max(cell, b.max_coord(d) - b.min_coord(d));
      // Not a structured binding: a lambda below uses `low` (clang refuses to capture bindings).
      const std::pair<Eigen::Vector3d, Eigen::Vector3d> box = mesh.bounding_box();
      const Eigen::Vector3d low = box.first;
      cell = std::max(cell, 1e-9 * std::max((box.second - low).norm(), 1e-300));
      auto cell_index = [&](double x, int d) { return static_cast<std::int64_t>(std::floor((x - low[d]) / cell)); };
      auto cell_key = [](std::int64_t i, std::int64_t j, std::int64_t k) {
        return (static_cast<std::uint64_t>(i) << 42) ^ (static_cast<std::uint64_t>(j) << 21) ^ static_cast<std::uint64_t>(k);
      };
      std::unordered_set<std::uint64_t> cells;
      for (const Box& b : fresh)
        for (std::int64_t i = cell_index(b.min_coord(0), 0); i <= cell_index(b.max_coord(0), 0); ++i)
          for (std::int64_t j = cell_index(b.min_coord(1), 1); j <= cell_index(b.max_coord(1), 1); ++j)
            for (std::int64_t k = cell_index(b.min_coord(2), 2); k <= cell_index(b.max_coord(2), 2); ++k) cells.insert(cell_key(i, j, k));
      std::vector<char> meets(n, 0);
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t t = r.begin(); t != r.end(); ++t) {
          const Box b = box_of(t);
          std::array<std::int64_t, 3> from{}, to{};
          std::int64_t count = 1;
          for (int d = 0; d < 3; ++d) {
            from[static_cast<std::size_t>(d)] = cell_index(b.min_coord(d), d);
            to[static_cast<std::size_t>(d)] = cell_index(b.max_coord(d), d);
            count *= to[static_cast<std::size_t>(d)] - from[static_cast<std::size_t>(d)] + 1;
          }
          bool found_cell = count > 64;  // a box much larger than the new ones: left to CGAL
          for (std::int64_t i = from[0]; i <= to[0] && !found_cell; ++i)
            for (std::int64_t j = from[1]; j <= to[1] && !found_cell; ++j)
              for (std::int64_t k = from[2]; k <= to[2] && !found_cell; ++k) found_cell = cells.count(cell_key(i, j, k)) > 0;
          meets[t] = found_cell;
        }
      });
      for (std::size_t t = 0; t < n; ++t)
        if (meets[t]) near.push_back(box_of(t));
      CGAL::box_intersection_d(fresh.begin(), fresh.end(), near.begin(), near.end(),
                               [&](const Box& a, const Box& b) { tested[a.info()] = tested[b.info()] = 1; });
    }
    std::vector<std::size_t> range;
    for (std::size_t t = 0; t < n; ++t)
      if (tested[t]) range.push_back(t);
    state->tested = range.size();
    state->reused = n - range.size();
    if (!range.empty()) {
      const auto sub_found = pairs_among(range);
      found.insert(found.end(), sub_found.begin(), sub_found.end());
    }
  } else if (manifold && n >= kSlabbedTest) {
    // The full test in slabs along the longest axis, in parallel: a pair that intersects has
    // boxes that overlap, and the lowest point of their overlap along the axis lies in a slab
    // that both boxes reach. (CGAL's own parallel test was no faster than its sequential one on
    // two cores: it shuffles the boxes.)
    const auto [low, high] = mesh.bounding_box();
    int axis = 0;
    for (int d = 1; d < 3; ++d)
      if (high[d] - low[d] > high[axis] - low[axis]) axis = d;
    std::vector<double> centre(n);
    for (std::size_t t = 0; t < n; ++t) {
      const auto& tri = mesh.triangles[t];
      centre[t] = (mesh.positions[static_cast<std::size_t>(tri[0])][axis] + mesh.positions[static_cast<std::size_t>(tri[1])][axis] +
                   mesh.positions[static_cast<std::size_t>(tri[2])][axis]) / 3;
    }
    // Slab borders at quantiles of the triangles' centres, so that the slabs are about equal.
    const std::size_t slabs = std::max<std::size_t>(2, 4 * static_cast<std::size_t>(tbb::this_task_arena::max_concurrency()));
    std::vector<double> sorted = centre;
    std::sort(sorted.begin(), sorted.end());
    std::vector<double> border{-std::numeric_limits<double>::infinity()};
    for (std::size_t k = 1; k < slabs; ++k) border.push_back(sorted[k * n / slabs]);
    border.push_back(std::numeric_limits<double>::infinity());
    std::vector<std::vector<FaceIndex>> slab(slabs);
    for (std::size_t t = 0; t < n; ++t) {
      const auto& tri = mesh.triangles[t];
      double from = std::numeric_limits<double>::infinity(), to = -from;
      for (const int v : tri) {
        from = std::min(from, mesh.positions[static_cast<std::size_t>(v)][axis]);
        to = std::max(to, mesh.positions[static_cast<std::size_t>(v)][axis]);
      }
      for (std::size_t k = 0; k < slabs; ++k)
        if (from <= border[k + 1] && to >= border[k]) slab[k].emplace_back(static_cast<Mesh::size_type>(t));
    }
    std::vector<std::size_t> all(n);
    std::iota(all.begin(), all.end(), std::size_t{0});
    Mesh check;
    cgal_mesh(all, true, check);
    std::vector<std::vector<std::pair<FaceIndex, FaceIndex>>> slab_found(slabs);
    tbb::parallel_for(std::size_t{0}, slabs, [&](std::size_t k) {
      PMP::self_intersections<CGAL::Sequential_tag>(slab[k], check, std::back_inserter(slab_found[k]));
    });
    for (const auto& f : slab_found) found.insert(found.end(), f.begin(), f.end());
    if (state) {
      state->tested = n;
      state->reused = 0;
    }
  } else {
    std::vector<std::size_t> all(n);
    std::iota(all.begin(), all.end(), std::size_t{0});
    Mesh check;
    cgal_mesh(all, manifold, check);
    PMP::self_intersections<CGAL::Parallel_if_available_tag>(check.faces(), check, std::back_inserter(found));
    if (state) {
      state->tested = n;
      state->reused = 0;
    }
  }
  for (const auto& [f, g] : found) {
    const auto i = static_cast<std::size_t>(f), j = static_cast<std::size_t>(g);
    result.emplace_back(std::min(i, j), std::max(i, j));
  }
  std::sort(result.begin(), result.end());
  result.erase(std::unique(result.begin(), result.end()), result.end());
  if (state) {
    state->valid = comparable;
    state->triangles.clear();
    state->pairs.clear();
    state->vertex_at.clear();
    if (comparable) {
      auto own_key = [&](std::size_t t) {
        return packed_triangle({static_cast<std::uint64_t>(mesh.triangles[t][0]), static_cast<std::uint64_t>(mesh.triangles[t][1]),
                                static_cast<std::uint64_t>(mesh.triangles[t][2])});
      };
      state->triangles.resize(n);
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t t = r.begin(); t != r.end(); ++t) state->triangles[t] = own_key(t);
      });
      sort_keys_by_high_bits(state->triangles, 42, mesh.num_vertices());
      for (const auto& [i, j] : result) state->pairs.emplace_back(own_key(i), own_key(j));
      state->vertex_at = std::move(vertex_at);
    }
  }
  return result;
}

}  // namespace volspline
