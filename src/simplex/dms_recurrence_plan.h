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

struct PlanNode {
  BarycentricFrame frame;                        // of W (a leaf: of its four knots)
  std::array<std::int32_t, 4> child{-1, -1, -1, -1};  // node of subset \ w_j (-1 in a flat node)
  std::array<std::int8_t, 4> w{};                // knot indices of W
  KnotMask mask = 0;                             // the subset
  std::int8_t degree = 0;
  bool flat = false;  // no four independent knots: M = 0 pointwise, a measure on a plane
  double inverse_volume = 0;                     // a leaf's 1/|det|
};

class DmsRecurrencePlan {
 public:
  /// Compiles the plan for the knots t_{c,i} = knots[c(n+1) + i] and the multi-indices `betas`;
  /// `index` is scratch (subset -> node while building).
  void build(const Eigen::Vector3d* knots, int degree, const std::vector<std::array<int, 4>>& betas,
             SubsetMemo& index);
  /// Whether the plan was built for exactly these knot coordinates.
  bool matches(const Eigen::Vector3d* knots) const;
  bool built() const { return built_; }
  /// Releases spare capacity (for plans kept per tetrahedron).
  void shrink_to_fit() {
    nodes_.shrink_to_fit();
    tops_.shrink_to_fit();
    scales_.shrink_to_fit();
  }
  std::size_t memory_bytes() const {
    return sizeof(*this) + nodes_.capacity() * sizeof(PlanNode) +
           (tops_.capacity() + scales_.capacity()) * sizeof(double);
  }

  int size() const { return static_cast<int>(nodes_.size()); }
  const PlanNode& node(int i) const { return nodes_[i]; }
  /// The node of V_β and |d(p_i, q_j, r_k, s_l)| of eq. 5, per β.
  int top(int b) const { return tops_[b]; }
  double scale(int b) const { return scales_[b]; }
  bool outside_box(const Eigen::Vector3d& x) const {
    return (x.array() < lo_.array()).any() || (x.array() > hi_.array()).any();
  }

  /// M(x | subset) of every node into out[0..size()).
  void values(const Eigen::Vector3d& x, double* out) const;
  /// ∫_a^b M(origin + t·direction | subset) dt of every node into out[0..size()); scratch holds
  /// 2·size() doubles.
  void line_integrals(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double a, double b, double* out,
                      double* scratch) const;

 private:
  int add(KnotMask subset, const KnotBinding& binding, SubsetMemo& index);

  std::vector<PlanNode> nodes_;
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
