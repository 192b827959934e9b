#include "volspline/mesh/self_intersections.h"

#include <algorithm>
#include <cstdint>
#include <functional>
#include <limits>
#include <unordered_map>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/box_intersection_d.h>

#include "volspline/mesh/mesh_checks.h"

namespace volspline {

// Not anonymous: SelfIntersectionRecord::State holds these types.
namespace self_intersections_detail {

namespace PMP = CGAL::Polygon_mesh_processing;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using FaceIndex = Mesh::Face_index;

struct PositionHash {
  std::size_t operator()(const std::array<double, 3>& p) const {
    std::size_t h = 0;
    for (const double x : p) h = h * 0x9e3779b97f4a7c15ull + std::hash<double>{}(x);
    return h;
  }
};

// + 0.0 makes -0 and +0 one key.
std::array<double, 3> position_key(const Eigen::Vector3d& p) { return {p.x() + 0.0, p.y() + 0.0, p.z() + 0.0}; }

// Vertex numbers below 2^21 packed into one key per triangle, smallest first (whether two
// triangles intersect does not depend on the order or the orientation of their corners).
constexpr std::size_t kPackedVertices = std::size_t{1} << 21;

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
  std::unordered_map<std::array<double, 3>, std::uint32_t, self_intersections_detail::PositionHash> vertex_at;
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
  std::vector<Point> points;
  points.reserve(mesh.num_vertices());
  for (const auto& p : mesh.positions) points.emplace_back(p.x(), p.y(), p.z());
  // A closed, oriented 2-manifold is a polygon mesh as it is; other soups are oriented first
  // (which splits non-manifold vertices, and reverses polygons but never reorders them, so the
  // mesh's faces keep the triangles' indices).
  const bool manifold = edge_statistics(mesh).closed_and_oriented() && nonmanifold_vertices(mesh) == 0;
  Mesh check;
  if (manifold) {
    std::vector<std::array<std::size_t, 3>> polygons(n);
    for (std::size_t t = 0; t < n; ++t)
      for (std::size_t j = 0; j < 3; ++j) polygons[t][j] = static_cast<std::size_t>(mesh.triangles[t][j]);
    PMP::polygon_soup_to_polygon_mesh(points, polygons, check);
  } else {
    std::vector<std::vector<std::size_t>> polygons;
    polygons.reserve(n);
    for (const auto& t : mesh.triangles)
      polygons.push_back({static_cast<std::size_t>(t[0]), static_cast<std::size_t>(t[1]), static_cast<std::size_t>(t[2])});
    PMP::orient_polygon_soup(points, polygons);
    PMP::polygon_soup_to_polygon_mesh(points, polygons, check);
  }

  SelfIntersectionRecord::State* state = record ? record->state_.get() : nullptr;
  // This mesh's vertices by position (for the next test), and which of them the recorded mesh
  // had: none if two share a position.
  std::unordered_map<std::array<double, 3>, std::uint32_t, PositionHash> vertex_at;
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
    std::vector<std::uint32_t> earlier(mesh.num_vertices(), std::numeric_limits<std::uint32_t>::max());
    for (std::size_t v = 0; v < mesh.num_vertices(); ++v)
      if (const auto it = state->vertex_at.find(position_key(mesh.positions[v])); it != state->vertex_at.end()) earlier[v] = it->second;
    std::vector<std::uint64_t> key(n, kNew);
    // The recorded pairs' triangles, found where they still are.
    std::unordered_map<std::uint64_t, std::size_t> index;
    for (const auto& [a, b] : state->pairs) {
      index.emplace(a, n);
      index.emplace(b, n);
    }
    for (std::size_t t = 0; t < n; ++t) {
      std::array<std::uint64_t, 3> v{};
      bool known = true;
      for (std::size_t j = 0; j < 3; ++j) {
        const std::uint32_t e = earlier[static_cast<std::size_t>(mesh.triangles[t][j])];
        known = known && e != std::numeric_limits<std::uint32_t>::max();
        v[j] = e;
      }
      if (!known) continue;
      const std::uint64_t k = packed_triangle(v);
      if (!std::binary_search(state->triangles.begin(), state->triangles.end(), k)) continue;
      key[t] = k;
      if (const auto it = index.find(k); it != index.end()) it->second = t;
    }
    // Pairs of triangles both in the earlier mesh: as found then.
    for (const auto& [a, b] : state->pairs) {
      const std::size_t i = index.at(a), j = index.at(b);
      if (i < n && j < n) result.emplace_back(std::min(i, j), std::max(i, j));
    }
    // Pairs with a new triangle: both lie among the new triangles and those whose (closed)
    // boxes meet a new one's.
    using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::size_t>;
    std::vector<Box> all, fresh;
    all.reserve(n);
    for (std::size_t t = 0; t < n; ++t) {
      const auto& tri = mesh.triangles[t];
      all.emplace_back(points[static_cast<std::size_t>(tri[0])].bbox() + points[static_cast<std::size_t>(tri[1])].bbox() +
                           points[static_cast<std::size_t>(tri[2])].bbox(),
                       t);
      if (key[t] == kNew) fresh.push_back(all.back());
    }
    std::vector<char> tested(n, 0);
    if (!fresh.empty())
      CGAL::box_intersection_d(fresh.begin(), fresh.end(), all.begin(), all.end(),
                               [&](const Box& a, const Box& b) { tested[a.info()] = tested[b.info()] = 1; });
    std::vector<FaceIndex> range;
    for (std::size_t t = 0; t < n; ++t)
      if (tested[t]) range.emplace_back(static_cast<Mesh::size_type>(t));
    state->tested = range.size();
    state->reused = n - range.size();
    if (!range.empty()) PMP::self_intersections<CGAL::Parallel_if_available_tag>(range, check, std::back_inserter(found));
  } else {
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
      for (std::size_t t = 0; t < n; ++t) state->triangles[t] = own_key(t);
      std::sort(state->triangles.begin(), state->triangles.end());
      for (const auto& [i, j] : result) state->pairs.emplace_back(own_key(i), own_key(j));
      state->vertex_at = std::move(vertex_at);
    }
  }
  return result;
}

}  // namespace volspline
