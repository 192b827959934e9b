#pragma once
// Triangles (a superset's) by the cubes of a uniform lattice their boxes meet. The contouring's
// box and segment queries are all about a coarse cell's size (a lattice edge or a point, grown by
// the superset's error): each looks in a few cubes, where a walk down CGAL's AABB tree from its
// root cost 9-19 % of every example's samples (2026-12-07). A query sees the candidates of its
// cubes each once and tests them with the same predicates and constructions as before
// (CGAL::do_intersect, CGAL::intersection), so the answers are the tree's. Only the order of a
// visit differs, and no caller depends on it: crossings are sorted along their edge, the
// triangles near a point by distance and index, and of two triangles of one sheet at the same
// distance the lower index is taken (the tree's order decided that before).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include "volspline/core/error.h"

namespace volspline {

using BucketTriangle = CGAL::Exact_predicates_inexact_constructions_kernel::Triangle_3;

class TriangleBuckets {
 public:
  // `triangles` must outlive the index; `size`: the cubes' edge, about a query box's extent.
  TriangleBuckets(const std::vector<BucketTriangle>& triangles, double size) : triangles_(triangles), size_(size) {
    if (!(size > 0) || !std::isfinite(size)) throw InvalidInput("the cube size must be positive and finite", "size");
    if (triangles.size() >= std::numeric_limits<std::uint32_t>::max())
      throw InvalidInput("at most 2^32 - 2 triangles, got " + std::to_string(triangles.size()), "triangles");
    boxes_.reserve(triangles.size());
    for (const BucketTriangle& t : triangles) {
      boxes_.push_back(t.bbox());
      low_ = low_ + boxes_.back();
    }
    // A cube's box as computed may miss a point whose computed cube index is that cube by a few
    // units in the last place of the coordinates: the test of a triangle against it is widened.
    double scale = size;
    for (int d = 0; d < 3 && !triangles.empty(); ++d) scale = std::max({scale, std::abs(low_.min(d)), std::abs(low_.max(d))});
    const double margin = 1e-9 * scale;
    std::vector<std::vector<std::pair<std::uint64_t, std::uint32_t>>> chunk_entries(
        (triangles.size() + kChunk - 1) / kChunk);
    tbb::parallel_for(std::size_t{0}, chunk_entries.size(), [&](std::size_t c) {
      for (std::size_t t = c * kChunk; t < std::min(triangles.size(), (c + 1) * kChunk); ++t) {
        const auto [from, to] = range(boxes_[t]);
        // A triangle whose box spans more than two cubes in two directions (large, oblique) goes
        // only into the cubes it meets: its entries grow with its area, not its box's volume.
        const std::int64_t count = (to[0] - from[0] + 1) * (to[1] - from[1] + 1) * (to[2] - from[2] + 1);
        const bool every_cube = count <= 8 || triangles[t].is_degenerate();
        for (std::int64_t k = from[2]; k <= to[2]; ++k)
          for (std::int64_t j = from[1]; j <= to[1]; ++j)
            for (std::int64_t i = from[0]; i <= to[0]; ++i) {
              if (!every_cube) {
                const double x = low_.min(0) + static_cast<double>(i) * size_, y = low_.min(1) + static_cast<double>(j) * size_,
                             z = low_.min(2) + static_cast<double>(k) * size_;
                if (!CGAL::do_intersect(triangles[t], CGAL::Bbox_3(x - margin, y - margin, z - margin, x + size_ + margin,
                                                                   y + size_ + margin, z + size_ + margin)))
                  continue;
              }
              chunk_entries[c].emplace_back(key(i, j, k), static_cast<std::uint32_t>(t));
            }
      }
    });
    std::size_t total = 0;
    for (const auto& e : chunk_entries) total += e.size();
    std::vector<std::pair<std::uint64_t, std::uint32_t>> entries;
    entries.reserve(total);
    for (const auto& e : chunk_entries) entries.insert(entries.end(), e.begin(), e.end());
    tbb::parallel_sort(entries.begin(), entries.end());
    members_.resize(entries.size());
    cubes_.reserve(entries.size() / 2 + 1);
    for (std::size_t e = 0; e < entries.size(); ++e) {
      members_[e] = entries[e].second;
      if (e == 0 || entries[e].first != entries[e - 1].first) cubes_.emplace(entries[e].first, std::make_pair(e, e + 1));
      else cubes_[entries[e].first].second = e + 1;
    }
  }

  // Every triangle that meets `box` (closed), and some others whose boxes meet it, each once,
  // until `visit` returns false; in no particular order (the callers' answers do not depend on
  // it). `visit` must not query this index again.
  template <class Visit>
  void visit_candidates(const CGAL::Bbox_3& box, Visit visit) const {
    // Triangles seen in this query, stamped with the query's number (per thread and per index,
    // freed with it; numbers only grow, so earlier queries' stamps never match).
    auto& [seen, query] = seen_.local();
    if (seen.size() < triangles_.size()) seen.resize(triangles_.size(), 0);
    if (++query == 0) {
      std::fill(seen.begin(), seen.end(), 0);
      query = 1;
    }
    const auto [from, to] = range(box);
    for (std::int64_t k = from[2]; k <= to[2]; ++k)
      for (std::int64_t j = from[1]; j <= to[1]; ++j)
        for (std::int64_t i = from[0]; i <= to[0]; ++i) {
          const auto it = cubes_.find(key(i, j, k));
          if (it == cubes_.end()) continue;
          for (std::size_t m = it->second.first; m < it->second.second; ++m) {
            const std::uint32_t t = members_[m];
            if (seen[t] == query) continue;
            seen[t] = query;
            if (CGAL::do_overlap(box, boxes_[t]) && !visit(static_cast<std::size_t>(t))) return;
          }
        }
  }

  // The triangles that meet `box` (CGAL's filtered triangle-box predicate), each once, until
  // `visit` returns false.
  template <class Visit>
  void visit_meeting(const CGAL::Bbox_3& box, Visit visit) const {
    visit_candidates(box, [&](std::size_t t) { return !CGAL::do_intersect(triangles_[t], box) || visit(t); });
  }

  // Triangle entries of all cubes (for tests of the index's size).
  std::size_t entries() const { return members_.size(); }

  bool any_meets(const CGAL::Bbox_3& box) const {
    bool found = false;
    visit_meeting(box, [&](std::size_t) { return !(found = true); });
    return found;
  }

 private:
  static constexpr std::size_t kChunk = 4096;
  // Cube coordinates from the lowest corner of all boxes, clamped to [0, 2^21) each (a query
  // beyond the triangles' box meets cubes that hold none, or the border cubes, a superset of its
  // own: still every triangle its box meets).
  // Empty (from > to) where the box misses the triangles' box.
  std::pair<std::array<std::int64_t, 3>, std::array<std::int64_t, 3>> range(const CGAL::Bbox_3& b) const {
    std::array<std::int64_t, 3> from{}, to{};
    for (int d = 0; d < 3; ++d) {
      const auto du = static_cast<std::size_t>(d);
      if (!(b.max(d) >= low_.min(d) && b.min(d) <= low_.max(d))) return {{1, 1, 1}, {0, 0, 0}};
      from[du] = cube_index(b.min(d), d);
      to[du] = cube_index(b.max(d), d);
    }
    return {from, to};
  }
  // Clamped to the cubes of the triangles' box (fewer than 2^21 per direction: the size is a
  // coarse cell's, and the contouring's grid of those is checked smaller).
  std::int64_t cube_index(double x, int d) const {
    const double c = std::floor((x - low_.min(d)) / size_);
    const double last = std::floor((low_.max(d) - low_.min(d)) / size_);
    return static_cast<std::int64_t>(std::clamp(c, 0.0, std::min(last, static_cast<double>((1 << 21) - 1))));
  }
  static std::uint64_t key(std::int64_t i, std::int64_t j, std::int64_t k) {
    return (static_cast<std::uint64_t>(k) << 42) | (static_cast<std::uint64_t>(j) << 21) | static_cast<std::uint64_t>(i);
  }

  const std::vector<BucketTriangle>& triangles_;
  std::vector<CGAL::Bbox_3> boxes_;
  double size_;
  CGAL::Bbox_3 low_{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                    std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                    -std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  std::vector<std::uint32_t> members_;
  std::unordered_map<std::uint64_t, std::pair<std::size_t, std::size_t>> cubes_;
  mutable tbb::enumerable_thread_specific<std::pair<std::vector<std::uint32_t>, std::uint32_t>> seen_;
};

}  // namespace volspline
