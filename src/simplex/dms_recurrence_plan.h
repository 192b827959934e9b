#pragma once
// The recurrence of eq. 1 for all basis functions of one DMS tetrahedron, compiled once per knot
// configuration: the four knots W of every subset (the last knot of each cloud, completed
// greedily where a cloud is missing; dms_recurrence_plan.cpp), and so their barycentric frames,
// do not depend on the point. The plan lists the subsets
// the V_β reach in an order where children come first; evaluating at a point is one pass over it
// (barycentric coordinates, a weighted sum of two to four children, or the half-open test at the
// leaves), without choices, hashing or allocation.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "simplex_recurrence.h"

namespace volspline::simplex_detail {

/// A subset of at least five knots: eq. 1 with W and its frame, over the children.
struct PlanNode {
  BarycentricFrame frame;                             // of W
  std::array<std::int32_t, 4> child{-1, -1, -1, -1};  // node of subset \ w_j (-1 in a flat node)
  std::array<std::int8_t, 4> w{};                     // knot indices of W
  KnotMask mask = 0;                                  // the subset
  std::int8_t degree = 0;
  bool flat = false;  // no four independent knots: M = 0 pointwise, a measure on a plane
};

/// A four-knot subset in the layout of the evaluation loop: λ_j(x) = g_j·(x - origin) for
/// j = 1..3, λ_0 = 1 - λ_1 - λ_2 - λ_3, M = 1/|det| on the half-open tetrahedron (0 for a flat
/// four, whose g are 0).
struct PlanLeaf {
  std::array<double, 3> origin;
  std::array<double, 9> g;  // g_1, g_2, g_3
  double inverse_volume;
  KnotMask mask;
  std::array<std::int8_t, 4> w;  // its knots

  std::array<double, 4> lambda(const Eigen::Vector3d& x) const {
    const double rx = x.x() - origin[0];
    const double ry = x.y() - origin[1];
    const double rz = x.z() - origin[2];
    const double l1 = g[0] * rx + g[1] * ry + g[2] * rz;
    const double l2 = g[3] * rx + g[4] * ry + g[5] * rz;
    const double l3 = g[6] * rx + g[7] * ry + g[8] * rz;
    return {1.0 - l1 - l2 - l3, l1, l2, l3};
  }
  std::array<double, 4> mu(const Eigen::Vector3d& v) const {
    const double m1 = g[0] * v.x() + g[1] * v.y() + g[2] * v.z();
    const double m2 = g[3] * v.x() + g[4] * v.y() + g[5] * v.z();
    const double m3 = g[6] * v.x() + g[7] * v.y() + g[8] * v.z();
    return {-m1 - m2 - m3, m1, m2, m3};
  }
};

class DmsRecurrencePlan {
 public:
  /// Compiles the plan for the knots t_{c,i} = knots[c(n+1) + i] and the multi-indices `betas`;
  /// `index` is scratch (subset -> node while building).
  void build(const Eigen::Vector3d* knots, int degree, const std::vector<std::array<int, 4>>& betas,
             SubsetMemo& index);
  /// Whether the plan was built for exactly these knot coordinates.
  bool matches(const Eigen::Vector3d* knots) const;
  /// Releases spare capacity (for plans kept per tetrahedron).
  void shrink_to_fit() {
    interior_.shrink_to_fit();
    leaves_.shrink_to_fit();
    tops_.shrink_to_fit();
    scales_.shrink_to_fit();
  }
  std::size_t memory_bytes() const {
    return sizeof(*this) + interior_.capacity() * sizeof(PlanNode) + leaves_.capacity() * sizeof(PlanLeaf) +
           (tops_.capacity() + scales_.capacity()) * sizeof(double);
  }

  /// Nodes are numbered leaves first (0..leaf_count()), then the larger subsets, children before
  /// parents.
  int size() const { return static_cast<int>(leaves_.size() + interior_.size()); }
  int leaf_count() const { return static_cast<int>(leaves_.size()); }
  /// A node numbered >= leaf_count().
  const PlanNode& interior(int i) const { return interior_[i - leaf_count()]; }
  /// The node of V_β and |d(p_i, q_j, r_k, s_l)| of eq. 5, per β.
  int top(int b) const { return tops_[b]; }
  double scale(int b) const { return scales_[b]; }
  /// The subset V_β of the b-th multi-index.
  KnotMask top_mask(int b) const {
    const int t = tops_[b];
    return t < leaf_count() ? leaves_[t].mask : interior(t).mask;
  }
  const Eigen::Vector3d* knots() const { return knots_.data(); }
  int knot_count() const { return knot_count_; }
  /// The index of the knot that x is, or -1.
  int knot_at(const Eigen::Vector3d& x) const { return simplex_detail::knot_at(x, knots_.data(), knot_count_); }
  bool outside_box(const Eigen::Vector3d& x) const {
    return (x.array() < lo_.array()).any() || (x.array() > hi_.array()).any();
  }

  /// M(x | subset) of every node into out[0..size()).
  void values(const Eigen::Vector3d& x, double* out) const { values(x, out, knot_at(x)); }
  /// The same where `knot` = knot_at(x) is known.
  void values(const Eigen::Vector3d& x, double* out, int knot) const;
  /// ∫_a^b M(origin + t·direction | subset) dt of every node into out[0..size()); scratch holds
  /// 2·size() doubles.
  void line_integrals(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double a, double b, double* out,
                      double* scratch) const;

 private:
  // Adds `subset` and the subsets it needs (depth first, so children come first); returns
  // -1 - its position in leaves_ for a leaf, its position in interior_ otherwise.
  int add(KnotMask subset, const KnotBinding& binding, SubsetMemo& index);

  std::vector<PlanLeaf> leaves_;
  std::vector<PlanNode> interior_;
  std::vector<int> tops_;
  std::vector<double> scales_;
  std::array<Eigen::Vector3d, kMaxRecurrenceKnots> knots_{};
  int knot_count_ = 0;
  int cloud_size_ = 0;
  Eigen::Vector3d lo_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d hi_ = Eigen::Vector3d::Zero();
  bool built_ = false;
};

}  // namespace volspline::simplex_detail
