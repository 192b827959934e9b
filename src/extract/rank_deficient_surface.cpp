#include "volspline/extract/rank_deficient_surface.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <unordered_map>
#include <utility>

#include <Eigen/Geometry>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include "volspline/analysis/jacobian_determinant.h"
#include "volspline/analysis/sub_jacobians.h"
#include "volspline/core/elapsed_time.h"
#include "volspline/core/error.h"
#include "volspline/mesh/parts.h"
#include "volspline/spline/bezier_extraction.h"

namespace volspline {

namespace {

using Clock = std::chrono::steady_clock;

constexpr int kMaxFinestLevel = 12;
// Spare coefficient buffers a thread keeps for the subdivision's halves (2 per split).
constexpr std::size_t kSpareBuffers = 64;
// Bits per lattice coordinate of a grid vertex key: four of them and a 4-bit edge direction fill
// 64 bits.
constexpr int kCoordinateBits = 15;
// Rounding margin of the Bernstein coefficients, relative to the products of the derivatives'
// largest coefficients (a heuristic bound, see docs/envelopes.md).
constexpr double kRelativeMargin = 1e-10;
// J123 counts as identically zero below this, relative to the same scale.
constexpr double kVanishingJacobian = 1e-11;

// Interpolation parameters within this of an edge's end snap to the end (to weld the vertices
// that rounding would set an ulp apart).
constexpr double kSnap = 1e-12;

using Lattice = std::array<std::int64_t, 4>;

struct Cell {
  int piece = 0;
  int level = 0;
  // Low corner in units of 2^-level of the piece.
  Lattice origin{0, 0, 0, 0};
  // Bezier: the four sub-Jacobians (four components); Cone: the points (three).
  BernsteinTensor<4> tensor;
};

class Subdivision {
 public:
  Subdivision(const BSplineHypervolume& map, const RankDeficientOptions& options, int level)
      : options_(options), level_(level), pieces_(bezier_pieces(map)) {
    for (int d = 0; d < 4; ++d) {
      breakpoints_[static_cast<std::size_t>(d)] = map.knot_vector(d).breakpoints();
      counts_[static_cast<std::size_t>(d)] = static_cast<int>(breakpoints_[static_cast<std::size_t>(d)].size()) - 1;
    }
    roots_.resize(pieces_.size());
    double largest_j123 = 0, reference_j123 = 0;
    std::array<double, 4> reference{0, 0, 0, 0};
    for (std::size_t p = 0; p < pieces_.size(); ++p) {
      const BSplineHypervolume& piece = pieces_[p];
      Cell& root = roots_[p];
      root.piece = static_cast<int>(p);
      BernsteinTensor<4> h;
      h.degrees = piece.degrees();
      h.components = piece.coefficient_size();
      h.coefficients = piece.homogeneous();
      // The scale of rounding errors: products of the largest derivative coefficients (and of
      // the point, for the homogeneous determinants).
      std::array<double, 4> derivative_max{};
      for (int d = 0; d < 4; ++d) {
        const auto f = bernstein_derivative(h, d, piece.domain_max(d) - piece.domain_min(d));
        derivative_max[static_cast<std::size_t>(d)] = bernstein_max_abs(f);
      }
      const double point_max = piece.is_rational() ? bernstein_max_abs(h) : 1.0;
      const auto& m = derivative_max;
      const std::array<double, 4> ref{m[0] * m[1] * m[2] * point_max, m[0] * m[1] * m[3] * point_max,
                                      m[0] * m[2] * m[3] * point_max, m[1] * m[2] * m[3] * point_max};
      for (std::size_t k = 0; k < 4; ++k) reference[k] = std::max(reference[k], ref[k]);
      reference_j123 = std::max(reference_j123, ref[0]);
      const SubJacobiansBernstein minors = sub_jacobian_coefficients(piece);
      largest_j123 = std::max(largest_j123, bernstein_max_abs(bernstein_components(minors.minors, 0)));
      root.tensor = options.bounds == JacobianBoundMethod::Bezier ? minors.minors : h;
    }
    if (!(largest_j123 > kVanishingJacobian * reference_j123)) {
      throw InvalidInput("generator is not a volume: its Jacobian vanishes identically");
    }
    for (std::size_t k = 0; k < 4; ++k) margins_[k] = kRelativeMargin * reference[k];
    if (options.bounds == JacobianBoundMethod::Bezier) {
      for (std::size_t p = 0; p < pieces_.size(); ++p) divide_out_face_factors(p, roots_[p].tensor);
    }
  }

  // A minor that vanishes on a face of the domain (a collapsed face: a cylinder's axis, where
  // the angle's derivative is zero, makes J123, J134 and J234 vanish there) is divided by the
  // face's linear factor, as often as it vanishes there. Inside the domain the factor is
  // positive, so the four minors vanish together at the same interior points as before; the
  // face itself is the face sweeps' business (docs/envelopes.md, "Collapsed faces"). Without the
  // division no certificate can exclude the cells along the face (every minor but one is zero
  // there, and the last changes sign along it), and they are all kept to the finest level: on
  // Fig. 7 8,192 of its 16,384 kept cells, along the axis. Only faces on the domain's boundary: a minor
  // vanishing on a knot plane inside vanishes at interior points, which must stay.
  void divide_out_face_factors(std::size_t piece, BernsteinTensor<4>& minors) {
    std::array<int, 4> position{};
    std::size_t index = piece;
    for (std::size_t d = 0; d < 4; ++d) {
      position[d] = static_cast<int>(index % static_cast<std::size_t>(counts_[d]));
      index /= static_cast<std::size_t>(counts_[d]);
    }
    for (int k = 0; k < 4; ++k) {
      const double margin = margins_[static_cast<std::size_t>(k)];
      BernsteinTensor<4> minor = bernstein_components(minors, k);
      if (!(bernstein_max_abs(minor) > margin)) continue;
      bool divided = false;
      for (int d = 0; d < 4; ++d) {
        for (int side = 0; side < 2; ++side) {
          const bool on_boundary = side == 0 ? position[static_cast<std::size_t>(d)] == 0
                                             : position[static_cast<std::size_t>(d)] == counts_[static_cast<std::size_t>(d)] - 1;
          if (!on_boundary) continue;
          while (minor.degrees[static_cast<std::size_t>(d)] > 0 && !(bernstein_max_abs(bernstein_face(minor, d, side)) > margin)) {
            minor = bernstein_divide_by_face(minor, d, side);
            divided = true;
          }
        }
      }
      if (!divided) continue;
      minor = bernstein_elevate(minor, minors.degrees);
      const std::size_t n = minors.count();
      for (std::size_t i = 0; i < n; ++i) minors.coefficients[4 * i + static_cast<std::size_t>(k)] = minor.coefficients[i];
      ++divided_minors_;
    }
  }

  const std::vector<Cell>& roots() const { return roots_; }
  const std::array<double, 4>& margins() const { return margins_; }
  const std::array<int, 4>& counts() const { return counts_; }

  // The global parameter of lattice coordinate g (units of 2^-L of a piece) along d: the same
  // number for the same g, whichever cell asks.
  double parameter(int d, std::int64_t g) const {
    const auto& bp = breakpoints_[static_cast<std::size_t>(d)];
    const std::int64_t c = g >> level_, m = g & ((std::int64_t{1} << level_) - 1);
    if (c >= counts_[static_cast<std::size_t>(d)]) return bp.back();
    const double fraction = std::ldexp(static_cast<double>(m), -level_);
    return bp[static_cast<std::size_t>(c)] + (bp[static_cast<std::size_t>(c) + 1] - bp[static_cast<std::size_t>(c)]) * fraction;
  }

  // The global lattice corner of a finest cell.
  Lattice global_origin(const Cell& cell) const {
    Lattice g{};
    std::size_t index = static_cast<std::size_t>(cell.piece);
    for (std::size_t d = 0; d < 4; ++d) {
      const std::int64_t c = static_cast<std::int64_t>(index % static_cast<std::size_t>(counts_[d]));
      index /= static_cast<std::size_t>(counts_[d]);
      g[d] = (c << level_) + cell.origin[d];
    }
    return g;
  }

  // Depth first; the kept finest cells of the subtree are appended to `kept` in a fixed order.
  void explore(const Cell& cell, std::vector<Lattice>& kept) {
    if (examined_.fetch_add(1) >= options_.max_cells) {
      unresolved_.fetch_add(1);
      return;
    }
    if (options_.progress) options_.progress->advance();
    if (excluded(cell, 4)) return;
    if (cell.level == level_) {
      kept.push_back(global_origin(cell));
      return;
    }
    Lattice origin{};
    for (std::size_t d = 0; d < 4; ++d) origin[d] = 2 * cell.origin[d];
    split_along(cell.piece, cell.level + 1, origin, cell.tensor, 0, kept);
  }

  void fill(RankDeficientStats& stats) const {
    stats.cells_examined = std::min<std::int64_t>(examined_.load(), options_.max_cells);
    stats.part_cells_examined = parts_examined_.load();
    stats.cells_excluded_by_sign = by_sign_.load();
    stats.cells_excluded_without_fold = without_fold_.load();
    stats.cells_excluded_by_hull = by_hull_.load();
    stats.cells_excluded_by_cone = by_cone_.load();
    stats.cells_unresolved = unresolved_.load();
    stats.budget_exhausted = stats.cells_unresolved > 0;
    stats.minors_divided_by_faces = divided_minors_;
  }

 private:
  // Whether a certificate excludes the cell, whose first `split` directions are at cell.level and
  // the others one level coarser (a part of a cell being split, below); counted by certificate.
  bool excluded(const Cell& cell, int split) {
    RankCertificate certificate = RankCertificate::None;
    if (options_.bounds == JacobianBoundMethod::Bezier) {
      certificate = bernstein_rank_certificate(cell.tensor, margins_);
    } else {
      const BSplineHypervolume& piece = pieces_[static_cast<std::size_t>(cell.piece)];
      std::array<double, 4> lengths{};
      for (int d = 0; d < 4; ++d) {
        lengths[static_cast<std::size_t>(d)] = std::ldexp(piece.domain_max(d) - piece.domain_min(d), -(d < split ? cell.level : cell.level - 1));
      }
      certificate = cone_rank_certificate(cell.tensor, lengths);
    }
    switch (certificate) {
      case RankCertificate::Sign: by_sign_.fetch_add(1); return true;
      case RankCertificate::NoFold: without_fold_.fetch_add(1); return true;
      case RankCertificate::Hull: by_hull_.fetch_add(1); return true;
      case RankCertificate::Cone: by_cone_.fetch_add(1); return true;
      case RankCertificate::None: break;
    }
    return false;
  }

  // A cell is split into its 16 children one direction at a time, u, v, w, then t, and each
  // half, quarter and eighth is tested before it is split further: the certificates are
  // monotone under subdivision (the coefficients of a part are convex combinations of the
  // whole's, so a sign, a weak sign, a separating direction or a cone that holds on the whole
  // holds on every part), so a part that is excluded takes its children with it and the kept
  // cells are the ones the 16 children tested one by one would keep. A surface in the 4-D
  // domain usually lies in one half along some directions: those halves are excluded after one
  // split instead of being split three more times. The tensors are large ((3p + 1)^4 4-vectors,
  // 300 KB for Fig. 7's rational minors; docs/performance.md), so the splits, not the tests,
  // were the subdivision's time. `part` has directions < d split to `level`; the halves along d
  // come from this thread's spare buffers. Visited low half first, so the kept cells come in
  // the order of the children's index 8u + 4v + 2w + t.
  void split_along(int piece, int level, const Lattice& origin, const BernsteinTensor<4>& part, int d, std::vector<Lattice>& kept) {
    std::array<Cell, 2> halves;
    {
      SplitScratch& scratch = scratch_.local();
      for (Cell& half : halves) half.tensor.coefficients = scratch.take_buffer();
    }
    bernstein_split(part, d, 0.5, halves[0].tensor, halves[1].tensor);
    std::array<std::vector<Lattice>, 2> half_kept;
    const auto visit = [&](std::size_t i) {
      Cell& half = halves[i];
      half.piece = piece;
      half.level = level;
      half.origin = origin;
      half.origin[static_cast<std::size_t>(d)] += static_cast<std::int64_t>(i);
      if (d == 3) {
        explore(half, half_kept[i]);
      } else {
        parts_examined_.fetch_add(1);
        if (!excluded(half, d + 1)) split_along(piece, level, half.origin, half.tensor, d + 1, half_kept[i]);
      }
      scratch_.local().give_back(std::move(half.tensor.coefficients));
    };
    tbb::parallel_invoke([&] { visit(0); }, [&] { visit(1); });
    for (const auto& k : half_kept) kept.insert(kept.end(), k.begin(), k.end());
  }

  const RankDeficientOptions& options_;
  int level_;
  std::vector<BSplineHypervolume> pieces_;
  std::array<std::vector<double>, 4> breakpoints_;
  std::array<int, 4> counts_{};
  std::array<double, 4> margins_{};
  std::vector<Cell> roots_;
  // Per thread: coefficient buffers of finished parts for the next split's halves (their sizes
  // are kept, so reusing one neither allocates nor zeroes). Buffers move between threads with
  // the cells; each thread keeps at most kSpareBuffers.
  struct SplitScratch {
    std::vector<std::vector<double>> spare;
    std::vector<double> take_buffer() {
      if (spare.empty()) return {};
      std::vector<double> buffer = std::move(spare.back());
      spare.pop_back();
      return buffer;
    }
    void give_back(std::vector<double>&& buffer) {
      if (spare.size() < kSpareBuffers) spare.push_back(std::move(buffer));
    }
  };
  tbb::enumerable_thread_specific<SplitScratch> scratch_;
  int divided_minors_ = 0;
  std::atomic<std::int64_t> examined_{0}, parts_examined_{0}, by_sign_{0}, without_fold_{0}, by_hull_{0}, by_cone_{0}, unresolved_{0};
};

std::uint64_t vertex_key(const Lattice& g) {
  std::uint64_t key = 0;
  for (std::size_t d = 0; d < 4; ++d) key = (key << kCoordinateBits) | static_cast<std::uint64_t>(g[d]);
  return key;
}

using Point4 = std::array<double, 4>;

// A point of J123 = 0 on a grid edge.
struct EdgePoint {
  std::uint64_t key = 0;
  Point4 x{};
  double f = 0;
};

// A vertex of the output on the segment between two edge points (keys ordered).
using SurfaceKey = std::pair<std::uint64_t, std::uint64_t>;

struct CellSurface {
  std::int64_t tetrahedra = 0;
  std::vector<std::array<SurfaceKey, 3>> triangles;
  // Triangles of lattice 2-faces on which the four minors vanish at every corner (below): a face
  // is shared by up to four cells, so these are merged once each.
  std::vector<std::array<SurfaceKey, 3>> face_triangles;
  std::vector<std::pair<SurfaceKey, Point4>> vertices;
};

// f = K . grad_uvw J123 with K = (J234, -J134, J124) (see the header) at x, from the second
// derivatives of s.
double rank_condition(const BSplineHypervolume& map, const Point4& x, const std::array<int, 16>& slot) {
  const std::vector<double> d = map.evaluate_derivatives(x, 2);
  const auto at = [&](int index) {
    return Eigen::Vector3d(Eigen::Map<const Eigen::Vector3d>(d.data() + 3 * slot[static_cast<std::size_t>(index)]));
  };
  // The pairs a <= b are stored row by row: (0,0) (0,1) (0,2) (0,3) (1,1) ... (3,3).
  const auto second = [&](int a, int b) {
    const int lo = std::min(a, b), hi = std::max(a, b);
    return at(4 + 4 * lo - lo * (lo - 1) / 2 + hi - lo);
  };
  const Eigen::Vector3d su = at(0), sv = at(1), sw = at(2), st = at(3);
  const Eigen::Vector3d K(jacobian_determinant(sv, sw, st), -jacobian_determinant(su, sw, st), jacobian_determinant(su, sv, st));
  double f = 0;
  for (int a = 0; a < 3; ++a) {
    const double gradient =
        jacobian_determinant(second(0, a), sv, sw) + jacobian_determinant(su, second(1, a), sw) + jacobian_determinant(su, sv, second(2, a));
    f += K[a] * gradient;
  }
  return f;
}

// |p . s_t| / (|p| |s_t|) for p the normal of the plane of s_u, s_v, s_w where they span one
// (rank 2): |K| / (|adj M|_F |s_t|), since K = adj(M) s_t = q (p . s_t) and adj M = q p^T, whose
// rows are s_v x s_w, s_w x s_u, s_u x s_v. 1 where M is singular of rank < 2 or s_t = 0.
double image_plane_sine(const double* derivatives) {
  const auto row = [&](int a) { return Eigen::Vector3d(Eigen::Map<const Eigen::Vector3d>(derivatives + 3 * a)); };
  const Eigen::Vector3d u = row(1), v = row(2), w = row(3), t = row(4);
  const double adjugate = std::sqrt(v.cross(w).squaredNorm() + w.cross(u).squaredNorm() + u.cross(v).squaredNorm());
  const Eigen::Vector3d K(jacobian_determinant(v, w, t), -jacobian_determinant(u, w, t), jacobian_determinant(u, v, t));
  const double denominator = adjugate * t.norm();
  return denominator > 0 ? std::min(1.0, K.norm() / denominator) : 1.0;
}

class CellMarcher {
 public:
  CellMarcher(const BSplineHypervolume& map, const Subdivision& subdivision, const std::array<int, 16>& slot)
      : map_(map), subdivision_(subdivision), slot_(slot) {
    // The margins are in units of the Bernstein minors, which for a rational map are those of
    // w^4 J (the homogeneous determinants): the weight's own spline scales a corner's minors.
    if (map.is_rational()) weight_.emplace(map.knot_vectors(), 1, map.weights());
  }

  CellSurface march(const Lattice& origin) const {
    std::array<Point4, 16> corner{};
    std::array<double, 16> j123{};
    std::array<Lattice, 16> lattice{};
    std::array<bool, 16> on_set{};
    const std::array<double, 4>& margins = subdivision_.margins();
    for (int c = 0; c < 16; ++c) {
      for (int d = 0; d < 4; ++d) {
        lattice[static_cast<std::size_t>(c)][static_cast<std::size_t>(d)] = origin[static_cast<std::size_t>(d)] + ((c >> d) & 1);
        corner[static_cast<std::size_t>(c)][static_cast<std::size_t>(d)] =
            subdivision_.parameter(d, lattice[static_cast<std::size_t>(c)][static_cast<std::size_t>(d)]);
      }
      const std::array<double, 4> minors = sub_jacobians_at(map_, corner[static_cast<std::size_t>(c)]);
      j123[static_cast<std::size_t>(c)] = minors[0];
      const double w = weight_ ? weight_->evaluate(corner[static_cast<std::size_t>(c)])[0] : 1.0;
      const double scale = w * w * w * w;
      bool zero = true;
      for (std::size_t k = 0; k < 4; ++k) zero = zero && std::abs(minors[k]) * scale <= margins[k];
      on_set[static_cast<std::size_t>(c)] = zero;
    }
    CellSurface out;
    // A rank-deficient set lying in a lattice 2-face (a generator symmetric about a dyadic
    // parameter: Fig. 7's bulge ridge u = 3/4, v = 1/2 turned about its own axis) vanishes at
    // the face's corners only to rounding. J123 changes sign across it only to one side and f
    // is zero on it, so the marching below sees the signs of rounding errors there and leaves
    // holes (84 % of Fig. 7's ridge covered at 2^-7). Where all four minors vanish to the
    // certificates' margins at a face's four corners, the face itself is the surface: two
    // triangles split at the diagonal from the smallest key, so that every cell sharing the face
    // splits it alike; the marching's triangles lying in such a face (slivers made of rounding
    // signs) are dropped (docs/envelopes.md, "Rank-deficient sets on the lattice").
    struct FlatFace {
      int a = 0, b = 0;
      Point4 low{}, high{};
    };
    std::vector<FlatFace> flat_faces;
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b)
        for (int base = 0; base < 16; ++base) {
          if (base & ((1 << a) | (1 << b))) continue;
          const std::array<int, 4> quad{base, base | (1 << a), base | (1 << a) | (1 << b), base | (1 << b)};
          bool flat = true;
          for (int c : quad) flat = flat && on_set[static_cast<std::size_t>(c)];
          if (!flat) continue;
          std::array<SurfaceKey, 4> key{};
          for (std::size_t i = 0; i < 4; ++i) {
            const std::uint64_t k = vertex_key(lattice[static_cast<std::size_t>(quad[i])]) << 4;
            key[i] = SurfaceKey{k, k};
            out.vertices.emplace_back(key[i], corner[static_cast<std::size_t>(quad[i])]);
          }
          const std::size_t first = static_cast<std::size_t>(
              std::min_element(key.begin(), key.end(), [](const SurfaceKey& x, const SurfaceKey& y) { return x.first < y.first; }) - key.begin());
          const SurfaceKey &p = key[first], &q = key[(first + 1) % 4], &r = key[(first + 2) % 4], &t = key[(first + 3) % 4];
          out.face_triangles.push_back({p, q, r});
          out.face_triangles.push_back({p, r, t});
          flat_faces.push_back({a, b, corner[static_cast<std::size_t>(quad[0])], corner[static_cast<std::size_t>(quad[2])]});
        }
    std::map<std::uint64_t, EdgePoint> points;
    // The edge point between corners a and b (one a subset of the other as bit masks, as on
    // every Kuhn edge), interpolated from the lower corner.
    const auto edge_point = [&](int a, int b) -> const EdgePoint& {
      if ((a & b) != a) std::swap(a, b);
      EdgePoint p;
      const double ja = j123[static_cast<std::size_t>(a)], jb = j123[static_cast<std::size_t>(b)];
      double s = ja / (ja - jb);
      // Where J123 vanishes at a corner (to rounding) the point is that corner, keyed as that
      // grid vertex (direction bits 0), so that every edge through the corner gives one point.
      const int at = s < kSnap ? a : (s > 1 - kSnap ? b : -1);
      if (at >= 0) s = at == a ? 0.0 : 1.0;
      for (std::size_t d = 0; d < 4; ++d) {
        const double xa = corner[static_cast<std::size_t>(a)][d], xb = corner[static_cast<std::size_t>(b)][d];
        p.x[d] = at == a ? xa : at == b ? xb : std::clamp(xa + (xb - xa) * s, std::min(xa, xb), std::max(xa, xb));
      }
      p.key = at >= 0 ? vertex_key(lattice[static_cast<std::size_t>(at)]) << 4
                      : (vertex_key(lattice[static_cast<std::size_t>(a)]) << 4) | static_cast<std::uint64_t>(a ^ b);
      auto it = points.find(p.key);
      if (it != points.end()) return it->second;
      p.f = rank_condition(map_, p.x, slot_);
      return points.emplace(p.key, p).first->second;
    };
    std::array<int, 4> axes{0, 1, 2, 3};
    do {
      std::array<int, 5> v{};
      for (int k = 0; k < 4; ++k) v[static_cast<std::size_t>(k) + 1] = v[static_cast<std::size_t>(k)] | (1 << axes[static_cast<std::size_t>(k)]);
      std::array<int, 5> positive{}, negative{};
      int np = 0, nn = 0;
      for (int c : v) {
        if (j123[static_cast<std::size_t>(c)] >= 0) positive[static_cast<std::size_t>(np++)] = c;
        else negative[static_cast<std::size_t>(nn++)] = c;
      }
      if (np == 0 || nn == 0) continue;
      // The minority side: one corner (Case I) or two (Case II).
      const bool fewer_positive = np < nn;
      const auto& few = fewer_positive ? positive : negative;
      const auto& many = fewer_positive ? negative : positive;
      const int nf = std::min(np, nn);
      if (nf == 1) {
        add_tetrahedron({&edge_point(few[0], many[0]), &edge_point(few[0], many[1]), &edge_point(few[0], many[2]),
                         &edge_point(few[0], many[3])},
                        out);
      } else {
        std::array<const EdgePoint*, 3> bottom{}, top{};
        for (std::size_t i = 0; i < 3; ++i) {
          bottom[i] = &edge_point(many[i], few[0]);
          top[i] = &edge_point(many[i], few[1]);
        }
        add_prism(bottom, top, out);
      }
    } while (std::next_permutation(axes.begin(), axes.end()));
    if (!flat_faces.empty()) {
      // Interpolation between points with equal coordinates keeps them exactly, so a vertex in
      // a face has the face's two fixed coordinates to the bit.
      std::map<SurfaceKey, Point4> at(out.vertices.begin(), out.vertices.end());
      const auto in_face = [&](const FlatFace& f, const Point4& x) {
        for (int d = 0; d < 4; ++d) {
          const auto i = static_cast<std::size_t>(d);
          if (d == f.a || d == f.b) {
            if (x[i] < f.low[i] || x[i] > f.high[i]) return false;
          } else if (x[i] != f.low[i]) {
            return false;
          }
        }
        return true;
      };
      std::erase_if(out.triangles, [&](const std::array<SurfaceKey, 3>& t) {
        return std::any_of(flat_faces.begin(), flat_faces.end(), [&](const FlatFace& f) {
          return in_face(f, at.at(t[0])) && in_face(f, at.at(t[1])) && in_face(f, at.at(t[2]));
        });
      });
    }
    return out;
  }

 private:
  // Dompierre et al. ("How to subdivide pyramids, prisms and hexahedra into tetrahedra", 1999):
  // every quad's diagonal from its smallest key; rotate (and flip) the prism so that its
  // smallest vertex is bottom[0], whose two quads then have diagonals from it, and the third
  // quad decides between the two remaining splits.
  void add_prism(std::array<const EdgePoint*, 3> bottom, std::array<const EdgePoint*, 3> top, CellSurface& out) const {
    std::size_t smallest = 0;
    bool on_top = false;
    std::uint64_t best = bottom[0]->key;
    for (std::size_t i = 0; i < 3; ++i) {
      if (bottom[i]->key < best) best = bottom[i]->key, smallest = i, on_top = false;
      if (top[i]->key < best) best = top[i]->key, smallest = i, on_top = true;
    }
    if (on_top) std::swap(bottom, top);
    std::rotate(bottom.begin(), bottom.begin() + static_cast<std::ptrdiff_t>(smallest), bottom.end());
    std::rotate(top.begin(), top.begin() + static_cast<std::ptrdiff_t>(smallest), top.end());
    // Vertices 1..6 of Dompierre: bottom 0, 1, 2 and top 0, 1, 2 (top i above bottom i).
    const EdgePoint *v1 = bottom[0], *v2 = bottom[1], *v3 = bottom[2], *v4 = top[0], *v5 = top[1], *v6 = top[2];
    if (std::min(v2->key, v6->key) < std::min(v3->key, v5->key)) {
      add_tetrahedron({v1, v2, v3, v6}, out);
      add_tetrahedron({v1, v2, v6, v5}, out);
    } else {
      add_tetrahedron({v1, v2, v3, v5}, out);
      add_tetrahedron({v1, v5, v3, v6}, out);
    }
    add_tetrahedron({v1, v5, v6, v4}, out);
  }

  // Marching tetrahedra of f on one tetrahedron of J123 = 0.
  void add_tetrahedron(const std::array<const EdgePoint*, 4>& t, CellSurface& out) const {
    ++out.tetrahedra;
    std::array<const EdgePoint*, 4> positive{}, negative{};
    int np = 0, nn = 0;
    for (const EdgePoint* p : t) {
      if (p->f >= 0) positive[static_cast<std::size_t>(np++)] = p;
      else negative[static_cast<std::size_t>(nn++)] = p;
    }
    if (np == 0 || nn == 0) return;
    const auto vertex = [&](const EdgePoint* a, const EdgePoint* b) {
      if (b->key < a->key) std::swap(a, b);
      const double s = a->f / (a->f - b->f);
      // Where f vanishes at an end (to rounding: within kSnap of it along the edge) the vertex
      // is that end, keyed by it alone, so that every tetrahedron edge through it gives the
      // same vertex rather than points an ulp apart.
      if (s < kSnap) {
        out.vertices.emplace_back(SurfaceKey{a->key, a->key}, a->x);
        return SurfaceKey{a->key, a->key};
      }
      if (s > 1 - kSnap) {
        out.vertices.emplace_back(SurfaceKey{b->key, b->key}, b->x);
        return SurfaceKey{b->key, b->key};
      }
      Point4 x{};
      for (std::size_t d = 0; d < 4; ++d) x[d] = a->x[d] + (b->x[d] - a->x[d]) * s;
      const SurfaceKey key{a->key, b->key};
      out.vertices.emplace_back(key, x);
      return key;
    };
    if (np == 1 || nn == 1) {
      const bool one_positive = np == 1;
      const EdgePoint* apex = one_positive ? positive[0] : negative[0];
      const auto& rest = one_positive ? negative : positive;
      out.triangles.push_back({vertex(apex, rest[0]), vertex(apex, rest[1]), vertex(apex, rest[2])});
      return;
    }
    // Two and two: the quad ac, ad, bd, bc (a, b positive; c, d negative), cut along ac-bd.
    const SurfaceKey ac = vertex(positive[0], negative[0]), ad = vertex(positive[0], negative[1]),
                     bd = vertex(positive[1], negative[1]), bc = vertex(positive[1], negative[0]);
    out.triangles.push_back({ac, ad, bd});
    out.triangles.push_back({ac, bd, bc});
  }

  const BSplineHypervolume& map_;
  const Subdivision& subdivision_;
  const std::array<int, 16>& slot_;
  std::optional<BSplineHypervolume> weight_;
};

struct SurfaceKeyHash {
  std::size_t operator()(const SurfaceKey& k) const {
    return static_cast<std::size_t>(k.first * 0x9E3779B97F4A7C15ULL ^ (k.second + 0x7F4A7C159E3779B9ULL + (k.first << 6)));
  }
};

}  // namespace

RankDeficientSurface rank_deficient_surface(const BSplineHypervolume& map, const RankDeficientOptions& options) {
  const auto start = Clock::now();
  if (map.dimension() != 3) {
    throw InvalidInput("the rank-deficient set needs a map into R^3, got dimension " + std::to_string(map.dimension()));
  }
  if (!(options.tolerance > 0 && options.tolerance <= 1)) throw InvalidInput("tolerance must be in (0, 1]");
  if (options.max_cells < 1) throw InvalidInput("max_cells must be at least 1");
  if (!(options.cusp_sine >= 0 && options.cusp_sine <= 1)) throw InvalidInput("cusp_sine must be in [0, 1]");
  if (options.bounds == JacobianBoundMethod::Cone && map.is_rational()) {
    throw InvalidInput("cone bounds need a polynomial map (the cones bound polynomial derivatives); use bezier bounds");
  }
  const int level = std::max(0, static_cast<int>(std::ceil(std::log2(1.0 / options.tolerance) - 1e-12)));
  if (level > kMaxFinestLevel) throw InvalidInput("tolerance below 2^-12 of a Bézier piece is not supported");
  for (int d = 0; d < 4; ++d) {
    if (static_cast<std::int64_t>(map.knot_vector(d).num_spans()) << level >= (std::int64_t{1} << kCoordinateBits)) {
      throw InvalidInput("more than 2^15 finest cells along parameter " + std::to_string(d));
    }
  }
  RankDeficientSurface result;
  result.stats.finest_level = level;

  // Subdivision.
  const auto subdivision_start = Clock::now();
  Subdivision subdivision(map, options, level);
  std::vector<Lattice> kept;
  {
    ProgressPhase phase(options.progress, "subdivision", 0, "cells");
    const auto& roots = subdivision.roots();
    std::vector<std::vector<Lattice>> root_kept(roots.size());
    tbb::parallel_for(std::size_t{0}, roots.size(), [&](std::size_t r) { subdivision.explore(roots[r], root_kept[r]); });
    for (const auto& k : root_kept) kept.insert(kept.end(), k.begin(), k.end());
  }
  subdivision.fill(result.stats);
  result.stats.cells_kept = static_cast<std::int64_t>(kept.size());
  result.stats.seconds_subdivision = seconds_since(subdivision_start);

  // Marching 4-simplices, then tetrahedra, per cell; merged in cell order.
  const auto marching_start = Clock::now();
  const auto indices = derivative_multi_indices<4>(2);
  // slot[0..3]: s_u..s_t; slot[4 + ...]: second derivatives (a <= b) in row-major upper order.
  std::array<int, 16> slot{};
  {
    int n = 0;
    for (int a = 0; a < 4; ++a) {
      for (int b = a; b < 4; ++b) {
        std::array<int, 4> alpha{0, 0, 0, 0};
        alpha[static_cast<std::size_t>(a)] += 1;
        alpha[static_cast<std::size_t>(b)] += 1;
        slot[static_cast<std::size_t>(4 + n++)] = static_cast<int>(std::find(indices.begin(), indices.end(), alpha) - indices.begin());
      }
      std::array<int, 4> alpha{0, 0, 0, 0};
      alpha[static_cast<std::size_t>(a)] = 1;
      slot[static_cast<std::size_t>(a)] = static_cast<int>(std::find(indices.begin(), indices.end(), alpha) - indices.begin());
    }
  }
  std::vector<CellSurface> surfaces(kept.size());
  {
    ProgressPhase phase(options.progress, "marching", static_cast<double>(kept.size()), "cells");
    const CellMarcher marcher(map, subdivision, slot);
    tbb::parallel_for(std::size_t{0}, kept.size(), [&](std::size_t c) {
      surfaces[c] = marcher.march(kept[c]);
      phase.advance();
    });
  }
  std::unordered_map<SurfaceKey, int, SurfaceKeyHash> welded;
  std::vector<Point4> domain_points;
  std::vector<std::array<int, 3>> triangles;
  std::set<std::array<int, 3>> lattice_faces;
  for (const CellSurface& s : surfaces) {
    result.stats.tetrahedra += s.tetrahedra;
    for (const auto& [key, x] : s.vertices) {
      if (welded.emplace(key, static_cast<int>(domain_points.size())).second) domain_points.push_back(x);
    }
    for (const auto& tri : s.triangles) {
      const std::array<int, 3> t{welded.at(tri[0]), welded.at(tri[1]), welded.at(tri[2])};
      // Collapsed where f or J123 vanished exactly at a sample.
      if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;
      triangles.push_back(t);
    }
    for (const auto& tri : s.face_triangles) {
      std::array<int, 3> t{welded.at(tri[0]), welded.at(tri[1]), welded.at(tri[2])};
      std::array<int, 3> sorted = t;
      std::sort(sorted.begin(), sorted.end());
      if (lattice_faces.insert(sorted).second) triangles.push_back(t);
    }
  }
  result.stats.lattice_face_triangles = static_cast<std::int64_t>(lattice_faces.size());
  result.stats.seconds_marching = seconds_since(marching_start);

  const auto mapping_start = Clock::now();
  const std::size_t n = domain_points.size();
  std::vector<Eigen::Vector3d> positions(n);
  std::vector<double> plane_sine(n);
  {
    ProgressPhase phase(options.progress, "mapping", static_cast<double>(n), "vertices");
    tbb::parallel_for(std::size_t{0}, n, [&](std::size_t i) {
      const std::vector<double> d = map.evaluate_derivatives(domain_points[i], 1);
      positions[i] = Eigen::Vector3d(d[0], d[1], d[2]);
      plane_sine[i] = image_plane_sine(d.data());
      phase.advance();
    });
  }
  // Drop the cusp sheets (every vertex with s_t well out of the image plane), then the vertices
  // no triangle uses, renumbering in order.
  std::vector<int> renumbered(n, -1);
  for (const auto& t : triangles) {
    if (plane_sine[static_cast<std::size_t>(t[0])] > options.cusp_sine && plane_sine[static_cast<std::size_t>(t[1])] > options.cusp_sine &&
        plane_sine[static_cast<std::size_t>(t[2])] > options.cusp_sine) {
      ++result.stats.triangles_at_cusps;
      continue;
    }
    std::array<int, 3> kept_triangle{};
    for (std::size_t k = 0; k < 3; ++k) {
      int& index = renumbered[static_cast<std::size_t>(t[k])];
      if (index < 0) {
        index = static_cast<int>(result.mesh.positions.size());
        const Point4& x = domain_points[static_cast<std::size_t>(t[k])];
        result.mesh.positions.push_back(positions[static_cast<std::size_t>(t[k])]);
        result.mesh.parameters.emplace_back(x[0], x[1], x[2]);
        result.t.push_back(x[3]);
      }
      kept_triangle[k] = index;
    }
    result.mesh.add_triangle(kept_triangle[0], kept_triangle[1], kept_triangle[2], Part::SweepRankDeficient);
  }
  result.stats.triangles = static_cast<std::int64_t>(result.mesh.triangles.size());
  result.stats.seconds_mapping = seconds_since(mapping_start);
  result.stats.seconds_total = seconds_since(start);
  return result;
}

}  // namespace volspline
