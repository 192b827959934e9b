#include "volspline/mesh/conforming_tetrahedra.h"

#include <algorithm>
#include <string>
#include <unordered_map>
#include <utility>

#include "volspline/core/error.h"

namespace volspline {

namespace {

struct LatticeHash {
  std::size_t operator()(const LatticePoint& p) const {
    std::uint64_t h = static_cast<std::uint64_t>(p[0]) * 0x9E3779B97F4A7C15ULL;
    h ^= static_cast<std::uint64_t>(p[1]) + 0x7F4A7C159E3779B9ULL + (h << 6) + (h >> 2);
    h ^= static_cast<std::uint64_t>(p[2]) + 0x94D049BB133111EBULL + (h << 6) + (h >> 2);
    return static_cast<std::size_t>(h);
  }
};

// A rectangle in a plane of constant lattice coordinate: the common part of a box's face and a
// face of the box across the plane (or the face itself on the boundary of the tiling). Fanned
// from its centre over every lattice point on its boundary, the same way from both sides.
struct Rectangle {
  int axis;
  std::int64_t plane;
  std::array<std::int64_t, 2> lo, hi;  // in the other two axes, ascending
  std::array<int, 2> boxes;            // boxes on the low and the high side (-1: none)
};

class ConformingTetrahedra {
 public:
  explicit ConformingTetrahedra(const std::vector<LatticeBox>& boxes) : boxes_(boxes), box_rectangles_(boxes.size()) {
    // Faces by plane: key (axis, coordinate) -> (box, side); side 0 means the box lies below
    // the plane (the face is its top).
    std::unordered_map<LatticePoint, std::vector<std::pair<int, int>>, LatticeHash> planes;
    for (std::size_t l = 0; l < boxes.size(); ++l) {
      for (int a = 0; a < 3; ++a) {
        const std::int64_t lo = boxes[l].origin[static_cast<std::size_t>(a)], hi = lo + boxes[l].extent[static_cast<std::size_t>(a)];
        planes[{a, hi, 0}].push_back({static_cast<int>(l), 0});
        planes[{a, lo, 0}].push_back({static_cast<int>(l), 1});
      }
    }
    for (const auto& [key, faces] : planes) add_plane(static_cast<int>(key[0]), key[1], faces);
    for (const LatticeBox& box : boxes) {
      for (int c = 0; c < 8; ++c) add_point(corner(box, c));
    }
    for (const Rectangle& r : rectangles_) {
      const int b = (r.axis + 1) % 3, c = (r.axis + 2) % 3;
      for (int k = 0; k < 4; ++k) {
        LatticePoint p{};
        p[static_cast<std::size_t>(r.axis)] = r.plane;
        p[static_cast<std::size_t>(b)] = (k & 1) ? r.hi[0] : r.lo[0];
        p[static_cast<std::size_t>(c)] = (k & 2) ? r.hi[1] : r.lo[1];
        add_point(p);
      }
    }
    for (auto& [key, coords] : lines_) {
      std::sort(coords.begin(), coords.end());
      coords.erase(std::unique(coords.begin(), coords.end()), coords.end());
    }
  }

  // Calls f(apex, face centre, q0, q1) for every tetrahedron of the kept boxes.
  template <class F>
  void for_each_tetrahedron(F&& f) const {
    for (std::size_t l = 0; l < boxes_.size(); ++l) {
      if (!boxes_[l].kept) continue;
      LatticePoint centre{};
      for (int d = 0; d < 3; ++d) centre[static_cast<std::size_t>(d)] = boxes_[l].origin[static_cast<std::size_t>(d)] + boxes_[l].extent[static_cast<std::size_t>(d)] / 2;
      for (int r : box_rectangles_[l]) {
        const auto ring = boundary_ring(rectangles_[static_cast<std::size_t>(r)]);
        const LatticePoint mid = rectangle_centre(rectangles_[static_cast<std::size_t>(r)]);
        for (std::size_t i = 0; i < ring.size(); ++i) f(centre, mid, ring[i], ring[(i + 1) % ring.size()]);
      }
    }
  }

 private:
  static LatticePoint corner(const LatticeBox& box, int c) {
    LatticePoint p = box.origin;
    for (int d = 0; d < 3; ++d) {
      if (c & (1 << d)) p[static_cast<std::size_t>(d)] += box.extent[static_cast<std::size_t>(d)];
    }
    return p;
  }

  void add_point(const LatticePoint& p) {
    for (int d = 0; d < 3; ++d) {
      LatticePoint key = p;
      key[static_cast<std::size_t>(d)] = -1 - d;  // the line along d through p
      lines_[key].push_back(p[static_cast<std::size_t>(d)]);
    }
  }

  void add_plane(int axis, std::int64_t plane, const std::vector<std::pair<int, int>>& faces) {
    const int b = (axis + 1) % 3, c = (axis + 2) % 3;
    auto face_of = [&](int box, std::array<std::int64_t, 2>& lo, std::array<std::int64_t, 2>& hi) {
      const LatticeBox& l = boxes_[static_cast<std::size_t>(box)];
      lo = {l.origin[static_cast<std::size_t>(b)], l.origin[static_cast<std::size_t>(c)]};
      hi = {lo[0] + l.extent[static_cast<std::size_t>(b)], lo[1] + l.extent[static_cast<std::size_t>(c)]};
    };
    std::vector<int> below, above;
    for (const auto& [box, side] : faces) (side == 0 ? below : above).push_back(box);
    auto add = [&](const Rectangle& r) {
      rectangles_.push_back(r);
      const int index = static_cast<int>(rectangles_.size()) - 1;
      for (int box : r.boxes) {
        if (box >= 0) box_rectangles_[static_cast<std::size_t>(box)].push_back(index);
      }
    };
    if (below.empty() || above.empty()) {
      // The boundary of the tiling: each face is its own rectangle.
      for (int box : below.empty() ? above : below) {
        Rectangle r{axis, plane, {}, {}, {below.empty() ? -1 : box, below.empty() ? box : -1}};
        face_of(box, r.lo, r.hi);
        add(r);
      }
      return;
    }
    // Faces on one side are dyadic squares that tile the plane's region; so are those on the
    // other side. Two dyadic intervals are nested or disjoint, so each overlap is the smaller
    // face in each axis. Sorting by the first coordinate keeps the scan short.
    std::sort(above.begin(), above.end(), [&](int x, int y) {
      return boxes_[static_cast<std::size_t>(x)].origin[static_cast<std::size_t>(b)] < boxes_[static_cast<std::size_t>(y)].origin[static_cast<std::size_t>(b)];
    });
    std::vector<std::int64_t> above_start;
    std::int64_t widest = 0;
    for (int box : above) {
      above_start.push_back(boxes_[static_cast<std::size_t>(box)].origin[static_cast<std::size_t>(b)]);
      widest = std::max(widest, boxes_[static_cast<std::size_t>(box)].extent[static_cast<std::size_t>(b)]);
    }
    for (int lower : below) {
      std::array<std::int64_t, 2> flo, fhi;
      face_of(lower, flo, fhi);
      auto it = std::lower_bound(above_start.begin(), above_start.end(), flo[0] - widest);
      for (std::size_t i = static_cast<std::size_t>(it - above_start.begin()); i < above.size() && above_start[i] < fhi[0]; ++i) {
        std::array<std::int64_t, 2> glo, ghi;
        face_of(above[i], glo, ghi);
        const std::array<std::int64_t, 2> lo{std::max(flo[0], glo[0]), std::max(flo[1], glo[1])};
        const std::array<std::int64_t, 2> hi{std::min(fhi[0], ghi[0]), std::min(fhi[1], ghi[1])};
        if (lo[0] >= hi[0] || lo[1] >= hi[1]) continue;
        add(Rectangle{axis, plane, lo, hi, {lower, above[i]}});
      }
    }
  }

  static LatticePoint rectangle_centre(const Rectangle& r) {
    LatticePoint p{};
    const int b = (r.axis + 1) % 3, c = (r.axis + 2) % 3;
    p[static_cast<std::size_t>(r.axis)] = r.plane;
    p[static_cast<std::size_t>(b)] = (r.lo[0] + r.hi[0]) / 2;
    p[static_cast<std::size_t>(c)] = (r.lo[1] + r.hi[1]) / 2;
    return p;
  }

  // Every lattice point on the boundary of r, counter-clockwise in (b, c).
  std::vector<LatticePoint> boundary_ring(const Rectangle& r) const {
    const int b = (r.axis + 1) % 3, c = (r.axis + 2) % 3;
    std::vector<LatticePoint> ring;
    auto point = [&](std::int64_t x, std::int64_t y) {
      LatticePoint p{};
      p[static_cast<std::size_t>(r.axis)] = r.plane;
      p[static_cast<std::size_t>(b)] = x;
      p[static_cast<std::size_t>(c)] = y;
      return p;
    };
    // Points strictly between `from` and `to` on the line along `axis` through `through`.
    auto between = [&](LatticePoint through, int along, std::int64_t from, std::int64_t to) {
      LatticePoint key = through;
      key[static_cast<std::size_t>(along)] = -1 - along;
      std::vector<std::int64_t> out;
      const auto found = lines_.find(key);
      if (found == lines_.end()) return out;
      const auto& coords = found->second;
      const std::int64_t a = std::min(from, to), z = std::max(from, to);
      for (auto it = std::upper_bound(coords.begin(), coords.end(), a); it != coords.end() && *it < z; ++it) out.push_back(*it);
      if (from > to) std::reverse(out.begin(), out.end());
      return out;
    };
    const std::int64_t x0 = r.lo[0], x1 = r.hi[0], y0 = r.lo[1], y1 = r.hi[1];
    ring.push_back(point(x0, y0));
    for (auto x : between(point(x0, y0), b, x0, x1)) ring.push_back(point(x, y0));
    ring.push_back(point(x1, y0));
    for (auto y : between(point(x1, y0), c, y0, y1)) ring.push_back(point(x1, y));
    ring.push_back(point(x1, y1));
    for (auto x : between(point(x1, y1), b, x1, x0)) ring.push_back(point(x, y1));
    ring.push_back(point(x0, y1));
    for (auto y : between(point(x0, y1), c, y1, y0)) ring.push_back(point(x0, y));
    return ring;
  }

  const std::vector<LatticeBox>& boxes_;
  std::vector<Rectangle> rectangles_;
  std::vector<std::vector<int>> box_rectangles_;
  std::unordered_map<LatticePoint, std::vector<std::int64_t>, LatticeHash> lines_;
};

}  // namespace

ConformingTetrahedralMesh conforming_tetrahedra(const std::vector<LatticeBox>& boxes) {
  for (std::size_t l = 0; l < boxes.size(); ++l) {
    for (const std::int64_t e : boxes[l].extent) {
      if (e <= 0 || e % 2 != 0) {
        throw InvalidInput("a box of a conforming tiling needs positive, even extents, got " + std::to_string(e) + " in box " +
                           std::to_string(l));
      }
    }
  }
  ConformingTetrahedralMesh mesh;
  if (std::none_of(boxes.begin(), boxes.end(), [](const LatticeBox& b) { return b.kept; })) return mesh;
  const ConformingTetrahedra tets(boxes);
  std::unordered_map<LatticePoint, int, LatticeHash> ids;
  auto id = [&](const LatticePoint& p) {
    const auto [it, inserted] = ids.emplace(p, static_cast<int>(mesh.points.size()));
    if (inserted) mesh.points.push_back(p);
    return it->second;
  };
  tets.for_each_tetrahedron([&](const LatticePoint& a, const LatticePoint& b, const LatticePoint& c, const LatticePoint& d) {
    mesh.tetrahedra.push_back({id(a), id(b), id(c), id(d)});
  });
  return mesh;
}

}  // namespace volspline
