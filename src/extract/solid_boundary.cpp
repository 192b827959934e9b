#include "volspline/extract/solid_boundary.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <queue>
#include <string>
#include <unordered_map>

#include <Eigen/Geometry>

#include "volspline/core/error.h"
#include "volspline/core/format.h"
#include "volspline/core/progress.h"
#include "volspline/extract/face_tessellation.h"
#include "volspline/mesh/marching_tetrahedra.h"

namespace volspline {

namespace {

using Lattice = std::array<std::int64_t, 3>;
using Clock = std::chrono::steady_clock;

double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

struct LatticeHash {
  std::size_t operator()(const Lattice& p) const {
    std::uint64_t h = static_cast<std::uint64_t>(p[0]) * 0x9E3779B97F4A7C15ULL;
    h ^= static_cast<std::uint64_t>(p[1]) + 0x7F4A7C159E3779B9ULL + (h << 6) + (h >> 2);
    h ^= static_cast<std::uint64_t>(p[2]) + 0x94D049BB133111EBULL + (h << 6) + (h >> 2);
    return static_cast<std::size_t>(h);
  }
};

// J and its gradient from second derivatives (Joy–Duchaineau §6: J_u = |p_uu p_v p_w| +
// |p_u p_uv p_w| + |p_u p_v p_uw|, and likewise for v and w).
struct JacobianSample {
  double value;
  Eigen::Vector3d gradient;
};

JacobianSample jacobian_with_gradient(const double* d) {
  auto vec = [&](int alpha) { return Eigen::Vector3d(d[alpha * 3], d[alpha * 3 + 1], d[alpha * 3 + 2]); };
  const Eigen::Vector3d pu = vec(1), pv = vec(2), pw = vec(3), puu = vec(4), puv = vec(5), puw = vec(6), pvv = vec(7),
                        pvw = vec(8), pww = vec(9);
  auto det = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) { return a.dot(b.cross(c)); };
  JacobianSample s;
  s.value = det(pu, pv, pw);
  s.gradient = {det(puu, pv, pw) + det(pu, puv, pw) + det(pu, pv, puw), det(puv, pv, pw) + det(pu, pvv, pw) + det(pu, pv, pvw),
                det(puw, pv, pw) + det(pu, pvw, pw) + det(pu, pv, pww)};
  return s;
}

void check_options(const BoundaryOptions& o) {
  if (!(o.tolerance > 0) || !std::isfinite(o.tolerance)) {
    throw InvalidInput("tolerance must be a finite number > 0, got " + format_double(o.tolerance));
  }
  if (o.max_cells < 1) throw InvalidInput("the cell budget must be at least 1");
  if (o.min_level < 0 || o.min_level > 20) throw InvalidInput("min_level must be in 0..20, got " + std::to_string(o.min_level));
  if (o.resolution < 1 || o.resolution > 1024) throw InvalidInput("resolution must be in 1..1024, got " + std::to_string(o.resolution));
  if (o.face_resolution < 1 || o.face_resolution > 4096) {
    throw InvalidInput("face resolution must be in 1..4096, got " + std::to_string(o.face_resolution));
  }
}

// A leaf of the subdivision: its lattice box and whether the zero set may cross it.
struct Leaf {
  Lattice origin;
  Lattice extent;
  bool kept;
};

// A rectangle in a plane of constant lattice coordinate: the common part of a leaf's face and a
// face of the leaf across the plane (or the face itself on the domain boundary). Fanned from its
// centre over every lattice point on its boundary, the same way from both sides.
struct Rectangle {
  int axis;
  std::int64_t plane;
  std::array<std::int64_t, 2> lo, hi;  // in the other two axes, ascending
  std::array<int, 2> leaves;           // leaves on the low and the high side (-1: none)
};

// The conforming tetrahedral mesh of the kept cells, built from the whole leaf tiling.
class ConformingTetrahedra {
 public:
  explicit ConformingTetrahedra(const std::vector<Leaf>& leaves) : leaves_(leaves), leaf_rectangles_(leaves.size()) {
    // Faces by plane: key (axis, coordinate) -> (leaf, side); side 0 means the leaf lies below
    // the plane (the face is its top).
    std::unordered_map<Lattice, std::vector<std::pair<int, int>>, LatticeHash> planes;
    for (std::size_t l = 0; l < leaves.size(); ++l) {
      for (int a = 0; a < 3; ++a) {
        const std::int64_t lo = leaves[l].origin[static_cast<std::size_t>(a)], hi = lo + leaves[l].extent[static_cast<std::size_t>(a)];
        planes[{a, hi, 0}].push_back({static_cast<int>(l), 0});
        planes[{a, lo, 0}].push_back({static_cast<int>(l), 1});
      }
    }
    for (const auto& [key, faces] : planes) add_plane(static_cast<int>(key[0]), key[1], faces);
    for (const Leaf& leaf : leaves) {
      for (int c = 0; c < 8; ++c) add_point(corner(leaf, c));
    }
    for (const Rectangle& r : rectangles_) {
      const int b = (r.axis + 1) % 3, c = (r.axis + 2) % 3;
      for (int k = 0; k < 4; ++k) {
        Lattice p{};
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

  // Calls f(apex, face centre, q0, q1) for every tetrahedron of the kept leaves.
  template <class F>
  void for_each_tetrahedron(F&& f) const {
    for (std::size_t l = 0; l < leaves_.size(); ++l) {
      if (!leaves_[l].kept) continue;
      Lattice centre{};
      for (int d = 0; d < 3; ++d) centre[static_cast<std::size_t>(d)] = leaves_[l].origin[static_cast<std::size_t>(d)] + leaves_[l].extent[static_cast<std::size_t>(d)] / 2;
      for (int r : leaf_rectangles_[l]) {
        const auto ring = boundary_ring(rectangles_[static_cast<std::size_t>(r)]);
        const Lattice mid = rectangle_centre(rectangles_[static_cast<std::size_t>(r)]);
        for (std::size_t i = 0; i < ring.size(); ++i) f(centre, mid, ring[i], ring[(i + 1) % ring.size()]);
      }
    }
  }

 private:
  static Lattice corner(const Leaf& leaf, int c) {
    Lattice p = leaf.origin;
    for (int d = 0; d < 3; ++d) {
      if (c & (1 << d)) p[static_cast<std::size_t>(d)] += leaf.extent[static_cast<std::size_t>(d)];
    }
    return p;
  }

  void add_point(const Lattice& p) {
    for (int d = 0; d < 3; ++d) {
      Lattice key = p;
      key[static_cast<std::size_t>(d)] = -1 - d;  // the line along d through p
      lines_[key].push_back(p[static_cast<std::size_t>(d)]);
    }
  }

  void add_plane(int axis, std::int64_t plane, const std::vector<std::pair<int, int>>& faces) {
    const int b = (axis + 1) % 3, c = (axis + 2) % 3;
    auto face_of = [&](int leaf, std::array<std::int64_t, 2>& lo, std::array<std::int64_t, 2>& hi) {
      const Leaf& l = leaves_[static_cast<std::size_t>(leaf)];
      lo = {l.origin[static_cast<std::size_t>(b)], l.origin[static_cast<std::size_t>(c)]};
      hi = {lo[0] + l.extent[static_cast<std::size_t>(b)], lo[1] + l.extent[static_cast<std::size_t>(c)]};
    };
    std::vector<int> below, above;
    for (const auto& [leaf, side] : faces) (side == 0 ? below : above).push_back(leaf);
    auto add = [&](const Rectangle& r) {
      rectangles_.push_back(r);
      const int index = static_cast<int>(rectangles_.size()) - 1;
      for (int leaf : r.leaves) {
        if (leaf >= 0) leaf_rectangles_[static_cast<std::size_t>(leaf)].push_back(index);
      }
    };
    if (below.empty() || above.empty()) {
      // The boundary of the domain: each face is its own rectangle.
      for (int leaf : below.empty() ? above : below) {
        Rectangle r{axis, plane, {}, {}, {below.empty() ? -1 : leaf, below.empty() ? leaf : -1}};
        face_of(leaf, r.lo, r.hi);
        add(r);
      }
      return;
    }
    // Faces on one side are dyadic squares that tile the plane's region; so are those on the
    // other side. Two dyadic intervals are nested or disjoint, so each overlap is the smaller
    // face in each axis. Sorting by the first coordinate keeps the scan short.
    std::sort(above.begin(), above.end(), [&](int x, int y) {
      return leaves_[static_cast<std::size_t>(x)].origin[static_cast<std::size_t>(b)] < leaves_[static_cast<std::size_t>(y)].origin[static_cast<std::size_t>(b)];
    });
    std::vector<std::int64_t> above_start;
    std::int64_t widest = 0;
    for (int leaf : above) {
      above_start.push_back(leaves_[static_cast<std::size_t>(leaf)].origin[static_cast<std::size_t>(b)]);
      widest = std::max(widest, leaves_[static_cast<std::size_t>(leaf)].extent[static_cast<std::size_t>(b)]);
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

  static Lattice rectangle_centre(const Rectangle& r) {
    Lattice p{};
    const int b = (r.axis + 1) % 3, c = (r.axis + 2) % 3;
    p[static_cast<std::size_t>(r.axis)] = r.plane;
    p[static_cast<std::size_t>(b)] = (r.lo[0] + r.hi[0]) / 2;
    p[static_cast<std::size_t>(c)] = (r.lo[1] + r.hi[1]) / 2;
    return p;
  }

  // Every lattice point on the boundary of r, counter-clockwise in (b, c).
  std::vector<Lattice> boundary_ring(const Rectangle& r) const {
    const int b = (r.axis + 1) % 3, c = (r.axis + 2) % 3;
    std::vector<Lattice> ring;
    auto point = [&](std::int64_t x, std::int64_t y) {
      Lattice p{};
      p[static_cast<std::size_t>(r.axis)] = r.plane;
      p[static_cast<std::size_t>(b)] = x;
      p[static_cast<std::size_t>(c)] = y;
      return p;
    };
    // Points strictly between `from` and `to` on the line along `axis` through `through`.
    auto between = [&](Lattice through, int along, std::int64_t from, std::int64_t to) {
      Lattice key = through;
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

  const std::vector<Leaf>& leaves_;
  std::vector<Rectangle> rectangles_;
  std::vector<std::vector<int>> leaf_rectangles_;
  std::unordered_map<Lattice, std::vector<std::int64_t>, LatticeHash> lines_;
};

// Newton steps on J towards J = 0 from a vertex, staying in the domain and within `reach` of
// the start; kept only if |J| decreases.
Eigen::Vector3d snap_to_zero(const BSplineVolume& v, const Eigen::Vector3d& start, double reach) {
  Eigen::Vector3d x = start;
  double d[30];
  v.evaluate_derivatives({x[0], x[1], x[2]}, 2, d);
  JacobianSample s = jacobian_with_gradient(d);
  const double first = std::abs(s.value);
  // A vertex on a face of the domain is where the implicit surface meets a face patch: it moves
  // within that face only.
  Eigen::Vector3d free = Eigen::Vector3d::Ones();
  for (int e = 0; e < 3; ++e) {
    if (start[e] == v.domain_min(e) || start[e] == v.domain_max(e)) free[e] = 0;
  }
  for (int iteration = 0; iteration < 8; ++iteration) {
    s.gradient = s.gradient.cwiseProduct(free);
    const double g2 = s.gradient.squaredNorm();
    if (!(g2 > 0)) break;
    Eigen::Vector3d next = x - s.value / g2 * s.gradient;
    for (int e = 0; e < 3; ++e) next[e] = std::clamp(next[e], v.domain_min(e), v.domain_max(e));
    if ((next - start).norm() > reach) break;
    v.evaluate_derivatives({next[0], next[1], next[2]}, 2, d);
    const JacobianSample t = jacobian_with_gradient(d);
    if (!(std::abs(t.value) < std::abs(s.value))) break;
    x = next;
    s = t;
    if (std::abs(s.value) <= 1e-15 * first) break;
  }
  return x;
}

// Largest |J| over a 17^3 grid of the domain: the scale that relative figures refer to.
double sampled_jacobian_scale(const BSplineVolume& v) {
  std::array<std::vector<double>, 3> samples;
  for (int d = 0; d < 3; ++d) {
    for (int i = 0; i <= 16; ++i) samples[static_cast<std::size_t>(d)].push_back(v.domain_min(d) + (v.domain_max(d) - v.domain_min(d)) * i / 16);
  }
  const auto g = v.evaluate_grid(samples, 1);
  const std::size_t n = 17 * 17 * 17;
  double best = 0;
  for (std::size_t p = 0; p < n; ++p) {
    auto vec = [&](std::size_t alpha) { return Eigen::Vector3d(g[(alpha * n + p) * 3], g[(alpha * n + p) * 3 + 1], g[(alpha * n + p) * 3 + 2]); };
    best = std::max(best, std::abs(vec(1).dot(vec(2).cross(vec(3)))));
  }
  return best;
}

// Maps the marching-tetrahedra result through the volume into `out` (part 6), with statistics.
void finish_surface(const BSplineVolume& volume, MarchingTetrahedra& mt, const BoundaryOptions& options,
                    SolidBoundary& out) {
  auto t = Clock::now();
  const auto& verts = mt.vertices();
  if (options.snap) {
    const ProgressPhase phase(options.progress, "snap", static_cast<double>(verts.size()));
    // A vertex may move at most 5% of the largest domain extent: Newton steps that go further
    // have left the basin of the zero set the vertex came from.
    double extent = 0;
    for (int d = 0; d < 3; ++d) extent = std::max(extent, volume.domain_max(d) - volume.domain_min(d));
    for (std::size_t i = 0; i < verts.size(); ++i) {
      mt.set_vertex(static_cast<int>(i), snap_to_zero(volume, verts[i], 0.05 * extent));
      phase.advance();
    }
  }
  out.stats.seconds_snap = options.snap ? since(t) : 0;
  const ProgressPhase phase(options.progress, "mapping");
  t = Clock::now();
  std::vector<std::array<double, 3>> params(verts.size());
  for (std::size_t i = 0; i < verts.size(); ++i) params[i] = {verts[i][0], verts[i][1], verts[i][2]};
  const std::vector<double> d = params.empty() ? std::vector<double>{} : volume.evaluate_points(params, 2);
  double scale = sampled_jacobian_scale(volume);
  double max_j = 0, max_distance = 0;
  TriangleMesh& mesh = out.mesh;
  const int base = static_cast<int>(mesh.num_vertices());
  for (std::size_t i = 0; i < verts.size(); ++i) {
    const double* di = d.data() + i * 30;
    const JacobianSample s = jacobian_with_gradient(di);
    max_j = std::max(max_j, std::abs(s.value));
    const double g = s.gradient.norm();
    if (g > 0) max_distance = std::max(max_distance, std::abs(s.value) / g);
    mesh.add_vertex(Eigen::Vector3d(di[0], di[1], di[2]), verts[i]);
  }
  scale = std::max(scale, max_j);
  for (const auto& tri : mt.triangles()) mesh.add_triangle(base + tri[0], base + tri[1], base + tri[2], 6);
  out.stats.triangles[6] = static_cast<std::int64_t>(mt.triangles().size());
  out.stats.max_rel_jacobian_at_vertices = scale > 0 ? max_j / scale : 0;
  out.stats.max_domain_distance = max_distance;
  out.stats.seconds_isosurface += since(t);
}

SolidBoundary adaptive_zero_surface(const BSplineVolume& volume, const BoundaryOptions& options) {
  SolidBoundary out;
  auto t = Clock::now();
  // How many cells the subdivision will examine is not known beforehand (the share of the
  // domain finished says little: the cells along the zero set take nearly all the time), so it
  // reports the count.
  std::optional<ProgressPhase> phase(std::in_place, options.progress, "subdivision", 0, "cells");
  const JacobianSubdivision sub(volume, options.bounds);
  std::vector<Leaf> leaves;
  auto leaf_of = [](const JacobianCell& c, bool kept) {
    Leaf l{c.origin, {}, kept};
    for (int d = 0; d < 3; ++d) l.extent[static_cast<std::size_t>(d)] = JacobianSubdivision::extent(c, d);
    return l;
  };
  auto wider = [](const JacobianCell& a, const JacobianCell& b) { return a.width() < b.width(); };
  std::priority_queue<JacobianCell, std::vector<JacobianCell>, decltype(wider)> queue(wider);
  for (auto& cell : sub.roots()) {
    ++out.stats.cells_examined;
    phase->advance();
    if (cell.excludes_zero()) {
      leaves.push_back(leaf_of(cell, false));
    } else {
      queue.push(std::move(cell));
    }
  }
  const double stop = options.tolerance * sub.scale();
  const bool by_width = options.stop == StopCriterion::Width || options.bounds == JacobianBoundMethod::Cone;
  while (!queue.empty()) {
    JacobianCell cell = queue.top();
    queue.pop();
    int direction = sub.split_direction(cell, by_width);
    // Cells keep an even lattice extent so that centres of cells and faces are lattice points.
    if (direction >= 0 && cell.level[static_cast<std::size_t>(direction)] >= JacobianSubdivision::kMaxLevel - 1) direction = -1;
    bool done = by_width ? cell.width() <= stop : sub.nonlinearity(cell) <= 0.5 * stop;
    for (int d = 0; d < 3; ++d) {
      if (cell.level[static_cast<std::size_t>(d)] < options.min_level &&
          (direction < 0 || cell.level[static_cast<std::size_t>(d)] < cell.level[static_cast<std::size_t>(direction)] || done)) {
        direction = d;
        done = false;
      }
    }
    if (done || direction < 0 || out.stats.cells_examined + 2 > options.max_cells) {
      leaves.push_back(leaf_of(cell, true));
      continue;
    }
    auto [a, b] = sub.split(cell, direction);
    phase->advance(2);
    for (JacobianCell* child : {&a, &b}) {
      ++out.stats.cells_examined;
      if (child->excludes_zero()) {
        leaves.push_back(leaf_of(*child, false));
      } else {
        queue.push(std::move(*child));
      }
    }
  }
  for (const Leaf& l : leaves) out.stats.cells_kept += l.kept ? 1 : 0;
  out.stats.seconds_subdivision = since(t);
  phase.reset();

  t = Clock::now();
  MarchingTetrahedra mt;
  if (out.stats.cells_kept > 0) {
    phase.emplace(options.progress, "tetrahedra");
    const ConformingTetrahedra tets(leaves);
    // Ids and J values of every lattice point used, evaluated once each.
    std::unordered_map<Lattice, int, LatticeHash> ids;
    std::vector<Lattice> points;
    std::vector<std::array<int, 4>> tetrahedra;
    auto id = [&](const Lattice& p) {
      const auto [it, inserted] = ids.emplace(p, static_cast<int>(points.size()));
      if (inserted) points.push_back(p);
      return it->second;
    };
    tets.for_each_tetrahedron([&](const Lattice& a, const Lattice& b, const Lattice& c, const Lattice& d) {
      tetrahedra.push_back({id(a), id(b), id(c), id(d)});
    });
    std::vector<std::array<double, 3>> params(points.size());
    std::vector<Eigen::Vector3d> domain(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      domain[i] = sub.parameter(points[i]);
      params[i] = {domain[i][0], domain[i][1], domain[i][2]};
    }
    const std::vector<double> d = volume.evaluate_points(params, 1);
    std::vector<double> value(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      const double* di = d.data() + i * 12;
      value[i] = Eigen::Vector3d(di[3], di[4], di[5]).dot(Eigen::Vector3d(di[6], di[7], di[8]).cross(Eigen::Vector3d(di[9], di[10], di[11])));
    }
    out.stats.seconds_tetrahedra = since(t);
    phase.emplace(options.progress, "marching", static_cast<double>(tetrahedra.size()));
    t = Clock::now();
    for (const auto& tet : tetrahedra) {
      std::array<MarchingTetrahedra::Sample, 4> s;
      for (std::size_t k = 0; k < 4; ++k) {
        const auto i = static_cast<std::size_t>(tet[k]);
        s[k] = {tet[k], domain[i], value[i]};
      }
      mt.add_tetrahedron(s);
      phase->advance();
    }
    out.stats.seconds_isosurface = since(t);
    phase.reset();
  }
  finish_surface(volume, mt, options, out);
  return out;
}

SolidBoundary uniform_zero_surface(const BSplineVolume& volume, const BoundaryOptions& options) {
  SolidBoundary out;
  auto t = Clock::now();
  std::optional<ProgressPhase> phase(std::in_place, options.progress, "sampling");
  const int n = options.resolution;
  std::array<std::vector<double>, 3> samples;
  for (int d = 0; d < 3; ++d) {
    for (int i = 0; i <= n; ++i) samples[static_cast<std::size_t>(d)].push_back(volume.domain_min(d) + (volume.domain_max(d) - volume.domain_min(d)) * i / n);
  }
  const auto g = volume.evaluate_grid(samples, 1);
  const std::size_t m = static_cast<std::size_t>(n + 1), count = m * m * m;
  std::vector<double> value(count);
  for (std::size_t p = 0; p < count; ++p) {
    auto vec = [&](std::size_t alpha) { return Eigen::Vector3d(g[(alpha * count + p) * 3], g[(alpha * count + p) * 3 + 1], g[(alpha * count + p) * 3 + 2]); };
    value[p] = vec(1).dot(vec(2).cross(vec(3)));
  }
  out.stats.cells_examined = static_cast<std::int64_t>(n) * n * n;
  out.stats.seconds_subdivision = since(t);
  phase.emplace(options.progress, "marching", n);
  t = Clock::now();
  MarchingTetrahedra mt;
  // Six tetrahedra around the main diagonal of each cube (Kuhn): neighbouring cubes agree on
  // the diagonals of their common faces, so the mesh is conforming.
  static constexpr int kKuhn[6][4] = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7}, {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};
  for (int k = 0; k < n; ++k) {
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        std::array<std::size_t, 8> c{};
        bool negative = false, positive = false;
        for (int q = 0; q < 8; ++q) {
          c[static_cast<std::size_t>(q)] = static_cast<std::size_t>(i + (q & 1)) + m * (static_cast<std::size_t>(j + ((q >> 1) & 1)) + m * static_cast<std::size_t>(k + ((q >> 2) & 1)));
          (value[c[static_cast<std::size_t>(q)]] < 0 ? negative : positive) = true;
        }
        if (!(negative && positive)) continue;
        ++out.stats.cells_kept;
        for (const auto& tet : kKuhn) {
          std::array<MarchingTetrahedra::Sample, 4> s;
          for (std::size_t q = 0; q < 4; ++q) {
            const std::size_t idx = c[static_cast<std::size_t>(tet[q])];
            const std::size_t ii = idx % m, jj = (idx / m) % m, kk = idx / (m * m);
            s[q] = {static_cast<std::int64_t>(idx), Eigen::Vector3d(samples[0][ii], samples[1][jj], samples[2][kk]), value[idx]};
          }
          mt.add_tetrahedron(s);
        }
      }
    }
    phase->advance();
  }
  out.stats.seconds_isosurface = since(t);
  phase.reset();
  finish_surface(volume, mt, options, out);
  return out;
}

}  // namespace

SolidBoundary jacobian_zero_surface(const BSplineVolume& volume, const BoundaryOptions& options) {
  check_options(options);
  if (volume.dimension() != 3) {
    throw InvalidInput("the boundary of a solid needs a volume in R^3, got control points of dimension " + std::to_string(volume.dimension()));
  }
  const auto start = Clock::now();
  SolidBoundary out = options.method == ZeroSurfaceMethod::Adaptive ? adaptive_zero_surface(volume, options)
                                                                    : uniform_zero_surface(volume, options);
  out.stats.seconds_total = since(start);
  return out;
}

SolidBoundary solid_boundary(const BSplineVolume& volume, const BoundaryOptions& options) {
  const auto start = Clock::now();
  SolidBoundary out = jacobian_zero_surface(volume, options);
  auto t = Clock::now();
  const ProgressPhase phase(options.progress, "faces");
  FaceTessellationOptions face_options;
  face_options.resolution = options.face_resolution;
  TriangleMesh faces = tessellate_faces(volume, face_options);
  for (int part : faces.parts) ++out.stats.triangles[static_cast<std::size_t>(part)];
  faces.append(out.mesh);
  out.mesh = std::move(faces);
  out.stats.seconds_faces = since(t);
  out.stats.seconds_total = since(start);
  return out;
}

}  // namespace volspline
