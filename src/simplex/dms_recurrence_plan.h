#pragma once
// The recurrence of eq. 1 for all basis functions of one DMS tetrahedron, compiled once per knot
// configuration: the four knots W of every subset (the last knot of each cloud, completed
// greedily where a cloud is missing; dms_recurrence_plan.cpp), and so their barycentric
// coordinates, do not depend on the point. The plan lists the subsets the V_β reach in an order
// where children come first; evaluating at a point is one pass over it (barycentric coordinates,
// a weighted sum of two to four children, or the half-open test at the leaves), without choices,
// hashing or allocation.
//
// Compact by sharing (scattered points miss the caches, so the bytes read per point are the
// cost): every barycentric coordinate is a determinant det[b - a, c - a, x - a] of a face (a, b, c)
// of W over det W, and the fours of one tetrahedron share most of their faces, the leaves and the
// W of larger subsets share most of their fours. A face stores its normal (b - a) × (c - a) once;
// per point each face costs one dot product with x - a, relative to a knot of the face (no
// absolute coordinates: the coordinate keeps the digits of x - a).
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "simplex_recurrence.h"

namespace volspline::simplex_detail {

/// Four knots w_0 < w_1 < w_2 < w_3 (indices). λ_j(x) = σ_j D_{face_j}(x) / det W with
/// σ = (-1, +1, -1, +1), face_j the other three knots in increasing order, D_{(a,b,c)}(x) =
/// det[b - a, c - a, x - a] (Cramer's rule: det W with w_j replaced by x, permuted so that x comes
/// last). inverse_det = 0 for a four that is flat within rounding (make_frame).
struct PlanFour {
  double inverse_det;
  std::array<std::uint16_t, 4> face;
  std::array<std::int8_t, 4> w;
};

/// A subset of at least five knots: eq. 1 over the four W (children[j] = subset \ w_j).
struct PlanNode {
  std::array<std::uint16_t, 4> child;
  std::uint16_t four;  // kFlatNode: no four independent knots, M = 0 pointwise (a measure on a plane)
  std::int8_t degree;
};

inline constexpr std::uint16_t kFlatNode = 0xFFFF;

class DmsRecurrencePlan {
 public:
  /// Compiles the plan for the knots t_{c,i} = knots[c(n+1) + i] and the multi-indices `betas`;
  /// `index` is scratch (subset -> node while building).
  void build(const Eigen::Vector3d* knots, int degree, const std::vector<std::array<int, 4>>& betas,
             SubsetMemo& index);
  /// Whether the plan was built for exactly these knot coordinates.
  bool matches(const Eigen::Vector3d* knots) const;
  /// Releases spare capacity (for plans kept per tetrahedron).
  void shrink_to_fit();
  std::size_t memory_bytes() const;

  /// Nodes are numbered leaves first (0..leaf_count(); leaf i is four i), then the larger subsets,
  /// children before parents.
  int size() const { return leaf_count_ + static_cast<int>(interior_.size()); }
  int leaf_count() const { return leaf_count_; }
  int face_count() const { return face_count_; }
  int four_count() const { return static_cast<int>(fours_.size()); }
  /// Doubles of scratch that values() and line_integrals() need besides their output.
  int work_size() const { return 2 * face_count(); }
  /// A node numbered >= leaf_count().
  const PlanNode& interior(int i) const { return interior_[static_cast<std::size_t>(i - leaf_count_)]; }
  /// Whether node i is a non-flat subset of at least five knots.
  bool has_frame(int i) const { return i >= leaf_count_ && interior(i).four != kFlatNode; }
  /// ∇λ_j of the four W of node i (has_frame(i)); the μ_j(e_x, e_y, e_z) of eq. 2. The children
  /// interior(i).child follow the same j.
  std::array<Eigen::Vector3d, 4> lambda_gradients(int i) const { return four_lambda_gradients(interior(i).four); }
  /// The four W of node i: a leaf's own knots, an interior node's W; -1 for a flat node.
  int node_four(int i) const {
    if (i < leaf_count_) return i;
    return interior(i).four == kFlatNode ? -1 : interior(i).four;
  }
  /// The knots of four q (increasing) and whether they are flat within rounding.
  const std::array<std::int8_t, 4>& four_knots(int q) const { return fours_[static_cast<std::size_t>(q)].w; }
  bool four_is_flat(int q) const { return fours_[static_cast<std::size_t>(q)].inverse_det == 0; }
  /// λ(x) of four q from the face determinants d of x (face_determinants), and ∇λ.
  std::array<double, 4> four_lambda(int q, const double* d) const { return lambda(q, d); }
  std::array<Eigen::Vector3d, 4> four_lambda_gradients(int q) const;
  /// D of every face at x (faces are grouped by their first knot: one x - a per group) into
  /// d[0..face_count()); values() leaves them in the first face_count() doubles of its work.
  void face_determinants(const Eigen::Vector3d& x, double* d) const;
  /// The node of V_β and |d(p_i, q_j, r_k, s_l)| of eq. 5, per β.
  int top(int b) const { return tops_[static_cast<std::size_t>(b)]; }
  double scale(int b) const { return scales_[static_cast<std::size_t>(b)]; }
  /// The subset V_β of the b-th multi-index.
  KnotMask top_mask(int b) const { return masks_[static_cast<std::size_t>(tops_[static_cast<std::size_t>(b)])]; }
  const Eigen::Vector3d* knots() const { return knots_.data(); }
  int knot_count() const { return knot_count_; }
  /// The index of the knot that x is, or -1.
  int knot_at(const Eigen::Vector3d& x) const { return simplex_detail::knot_at(x, knots_.data(), knot_count_); }
  bool outside_box(const Eigen::Vector3d& x) const {
    return x.x() < lo_.x() || x.y() < lo_.y() || x.z() < lo_.z() || x.x() > hi_.x() || x.y() > hi_.y() ||
           x.z() > hi_.z();
  }

  /// Asks the memory system for everything values() reads (scattered points find plans far from
  /// the caches; the requests for several candidate tetrahedra then overlap).
  void prefetch() const {
    const auto lines = [](const void* data, std::size_t bytes) {
      for (std::size_t offset = 0; offset < bytes; offset += 64) __builtin_prefetch(static_cast<const char*>(data) + offset);
    };
    lines(knots_.data(), static_cast<std::size_t>(knot_count_) * sizeof(Eigen::Vector3d));
    lines(face_begin_.data(), face_begin_.size() * sizeof(std::uint16_t));
    lines(normals_.data(), normals_.size() * sizeof(double));
    lines(fours_.data(), fours_.size() * sizeof(PlanFour));
    lines(interior_.data(), interior_.size() * sizeof(PlanNode));
    lines(tops_.data(), tops_.size() * sizeof(int));
    lines(scales_.data(), scales_.size() * sizeof(double));
  }
  /// M(x | subset) of every node into out[0..size()); `knot` = knot_at(x); work holds
  /// work_size() doubles (the face determinants of x are left in its first face_count()).
  void values(const Eigen::Vector3d& x, double* out, int knot, double* work) const;
  /// ∫_a^b M(origin + t·direction | subset) dt of every node into out[0..size()); scratch holds
  /// 2·size() + work_size() doubles.
  void line_integrals(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double a, double b, double* out,
                      double* scratch) const;

 private:
  struct Builder;
  // Adds `subset` and the subsets it needs (depth first, so children come first); returns
  // -1 - its position among the leaves for a leaf, its position in interior_ otherwise.
  int add(KnotMask subset, const KnotBinding& binding, Builder& builder);
  // λ of four q from the face determinants.
  [[gnu::always_inline]] std::array<double, 4> lambda(int q, const double* d) const {
    const PlanFour& f = fours_[static_cast<std::size_t>(q)];
    const double s = f.inverse_det;
    return {-s * d[f.face[0]], s * d[f.face[1]], -s * d[f.face[2]], s * d[f.face[3]]};
  }

  // Per face, grouped by first knot, by coordinate: x of every face, then y, then z (the dot
  // products of one group then run over consecutive doubles).
  std::vector<double> normals_;
  int face_count_ = 0;
  std::vector<std::uint16_t> face_begin_;       // faces of first knot k: face_begin_[k]..[k+1]
  std::vector<PlanFour> fours_;                 // the leaves' fours first
  std::vector<PlanNode> interior_;
  std::vector<KnotMask> masks_;  // per node
  std::vector<int> tops_;
  std::vector<double> scales_;
  std::array<Eigen::Vector3d, kMaxRecurrenceKnots> knots_{};
  int knot_count_ = 0;
  int cloud_size_ = 0;
  int leaf_count_ = 0;
  Eigen::Vector3d lo_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d hi_ = Eigen::Vector3d::Zero();
  bool built_ = false;
};

}  // namespace volspline::simplex_detail
