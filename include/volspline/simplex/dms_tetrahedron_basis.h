#pragma once
// The DMS basis functions of one domain tetrahedron (Hua, He and Qin 2004, §3.2, eqs. 4-5):
// N_β^I(x) = |d(p_i, q_j, r_k, s_l)| · M(x | V_β^I) for |β| = n, evaluated together with one memo
// over the knot subsets their recurrences share. Conventions of M: simplex/simplex_spline.h.
#include <Eigen/Core>
#include <array>
#include <memory>
#include <vector>

#include "volspline/simplex/simplex_spline.h"

namespace volspline {

/// The multi-indices β = (i, j, k, l) with |β| = degree, in this order: i from degree down to 0,
/// then j from degree - i down to 0, then k from degree - i - j down to 0, l the rest.
/// \throw InvalidInput for degree < 0.
std::vector<std::array<int, 4>> dms_multi_indices(int degree);

/// The position of β in dms_multi_indices(degree): C(n-i+2, 3) + C(n-i-j+1, 2) + l.
/// \throw InvalidInput when β has a negative entry or |β| != degree.
int dms_multi_index_position(const std::array<int, 4>& beta, int degree);

/// The basis functions of one tetrahedron at a point, in dms_multi_indices order.
struct DmsBasisValues {
  std::vector<double> values;              // N_β^I(x) = |d(p_i, q_j, r_k, s_l)| · M(x | V_β^I)
  std::vector<Eigen::Vector3d> gradients;  // filled for order >= 1
  std::vector<Eigen::Matrix3d> hessians;   // filled for order 2
};

/// The barycentric coordinates λ_m(x | W_β) with respect to each basis function's last knots
/// W_β = (p_i, q_j, r_k, s_l), β = (i, j, k, l), and their gradients (constant in x): the weights
/// of the DMS evaluation step (Hua–He–Qin §3.2, Dahmen–Micchelli–Seidel 1992), which evaluates a
/// degree-n spline with shared control points from the degree-(n−1) basis,
///   s(x) = Σ_I Σ_{|γ| = n−1} N_γ^I(x) Σ_m λ_m(x | W_γ) c_{γ+e^m}^I.
struct DmsLastKnotFrames {
  std::vector<std::array<double, 4>> lambdas;
  std::vector<std::array<Eigen::Vector3d, 4>> gradients;  // filled for order >= 1
};

namespace simplex_detail {
class DmsRecurrencePlan;
class DmsRecurrenceState;
}  // namespace simplex_detail

/// The point-independent part of the recurrences of one tetrahedron's basis functions: the knot
/// subsets the V_β reach, the four knots W of each and their barycentric frames (eqs. 1-2), in an
/// order where subsets come before the sets that use them. About 6 KiB for degree 2 and 17 KiB
/// for degree 3 (memory_bytes()). Build one per domain tetrahedron, and again after its knots move,
/// to evaluate scattered points without recompiling: compiling costs about 13 evaluations
/// (DmsTetrahedronBasis also keeps the last few it compiled from clouds).
class DmsTetrahedronPlan {
 public:
  DmsTetrahedronPlan();
  /// clouds as for DmsTetrahedronBasis::evaluate. \throw InvalidInput for a degree outside
  /// 0..kMaxSimplexSplineDegree or a non-finite knot.
  DmsTetrahedronPlan(int degree, const std::array<const Eigen::Vector3d*, 4>& clouds);
  ~DmsTetrahedronPlan();
  DmsTetrahedronPlan(DmsTetrahedronPlan&&) noexcept;
  DmsTetrahedronPlan& operator=(DmsTetrahedronPlan&&) noexcept;
  DmsTetrahedronPlan(const DmsTetrahedronPlan&) = delete;
  DmsTetrahedronPlan& operator=(const DmsTetrahedronPlan&) = delete;

  /// -1 for a default-constructed (empty) plan.
  int degree() const { return degree_; }
  /// Whether the plan was compiled from exactly these knot coordinates.
  bool matches(const std::array<const Eigen::Vector3d*, 4>& clouds) const;
  std::size_t memory_bytes() const;
  /// A hint: starts loading the plan into the caches (for the next tetrahedra to be evaluated,
  /// while others are).
  void prefetch() const;
  /// Whether the recurrence of every V_β steps with W_β = (p_i, q_j, r_k, s_l) (not flat within
  /// rounding), so that evaluation can also give λ(x | W_β) (DmsLastKnotFrames). True for knot
  /// clouds that satisfy the DMS conditions (validate_knot_clouds).
  bool has_last_knot_frames() const { return last_knot_frames_; }

 private:
  friend class DmsTetrahedronBasis;
  bool last_knot_frames_ = false;
  int degree_ = -1;
  std::unique_ptr<simplex_detail::DmsRecurrencePlan> plan_;
};

/// All basis functions N_β^I of one domain tetrahedron I = (p, q, r, s), memoised: the V_β^I of
/// eq. 4 share most of their subsets, so each distinct knot subset (a bitmask over the 4(n+1)
/// knots) is evaluated once per point. Eq. 1 steps with the last knot of each cloud,
/// (p_i, q_j, r_k, s_l) for V_β (non-degenerate by the DMS conditions), completed greedily in
/// subsets that miss a cloud (docs/simplex-splines.md). The recurrence is compiled per knot
/// configuration (DmsTetrahedronPlan); the object keeps the last 8 it compiled from clouds.
/// Reusable and allocation-free after the first calls (the scratch lives in the object; a new
/// configuration reuses a cached plan's storage); one object per thread.
class DmsTetrahedronBasis {
 public:
  /// \throw InvalidInput for a degree outside 0..kMaxSimplexSplineDegree.
  explicit DmsTetrahedronBasis(int degree);
  ~DmsTetrahedronBasis();
  DmsTetrahedronBasis(DmsTetrahedronBasis&&) noexcept;
  DmsTetrahedronBasis& operator=(DmsTetrahedronBasis&&) noexcept;
  DmsTetrahedronBasis(const DmsTetrahedronBasis&) = delete;
  DmsTetrahedronBasis& operator=(const DmsTetrahedronBasis&) = delete;

  int degree() const { return degree_; }
  /// The number of basis functions, (n+1)(n+2)(n+3)/6.
  int size() const { return static_cast<int>(multi_indices_.size()); }
  const std::vector<std::array<int, 4>>& multi_indices() const { return multi_indices_; }

  /// clouds[c] points at the n+1 knots t_{c,0..n} of vertex c (c = 0..3 for p, q, r, s); t_{c,0}
  /// is the vertex. Points outside the bounding box of the knots get zeros at once. A point that
  /// is one of the knots (a vertex, say) is evaluated by the memoised recurrence with W containing
  /// it instead of the compiled plan: the plan's fixed W cancel there (docs/simplex-splines.md,
  /// "Knots coplanar within rounding"); it costs a few plan evaluations.
  /// \throw InvalidInput for order outside 0..2 or a non-finite point or knot.
  void evaluate(const Eigen::Vector3d& x, const std::array<const Eigen::Vector3d*, 4>& clouds, int order,
                DmsBasisValues& out);
  /// The same from a plan compiled beforehand. \throw InvalidInput for an empty plan, a plan of
  /// another degree or order outside 0..2.
  void evaluate(const Eigen::Vector3d& x, const DmsTetrahedronPlan& plan, int order, DmsBasisValues& out);
  /// The same, and the barycentric coordinates of x with respect to each W_β (with their
  /// gradients for order >= 1; zeros where every value and gradient is 0). \throw InvalidInput
  /// as evaluate, or for a plan without has_last_knot_frames().
  void evaluate(const Eigen::Vector3d& x, const DmsTetrahedronPlan& plan, int order, DmsBasisValues& out,
                DmsLastKnotFrames& frames);

  /// ∫_a^b N_β^I(origin + t·direction) dt for every β (same order), memoised the same way
  /// (eq. 16 with boundary terms, simplex_spline_line_integral). \throw InvalidInput for a > b
  /// (or NaN), a non-finite origin, direction or knot.
  void line_integrals(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double a, double b,
                      const std::array<const Eigen::Vector3d*, 4>& clouds, std::vector<double>& out);
  /// The same from a plan compiled beforehand. \throw InvalidInput for a > b, an empty plan or a
  /// plan of another degree.
  void line_integrals(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double a, double b,
                      const DmsTetrahedronPlan& plan, std::vector<double>& out);

 private:
  const simplex_detail::DmsRecurrencePlan& checked(const DmsTetrahedronPlan& plan) const;
  void evaluate_plan(const Eigen::Vector3d& x, const simplex_detail::DmsRecurrencePlan& plan, int order,
                     DmsBasisValues& out);
  void line_integrals_plan(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double a, double b,
                           const simplex_detail::DmsRecurrencePlan& plan, std::vector<double>& out);

  int degree_;
  std::vector<std::array<int, 4>> multi_indices_;
  std::unique_ptr<simplex_detail::DmsRecurrenceState> state_;
};

}  // namespace volspline
