#pragma once
// Evaluating a DMS spline volume (simplex/dms_spline_volume.h) at scattered points: geometry,
// attributes and their gradients (Hua–He–Qin eqs. 2, 6, 7), zero outside the domain.
#include <array>
#include <functional>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "volspline/simplex/dms_spline_volume.h"

namespace volspline {

/// The value and gradient of a DMS spline volume at one point.
struct DmsSplinePoint {
  /// x lies in the closed domain Ω; outside, value and gradient are 0.
  bool inside = false;
  /// The tetrahedron of Ω that holds x (closed, the lowest index where several do), or -1.
  int tetrahedron = -1;
  /// x, y, z, g_1, ..., g_k (dimension() entries).
  Eigen::VectorXd value;
  /// d value / d x: dimension() rows, 3 columns; filled for order >= 1.
  Eigen::Matrix<double, Eigen::Dynamic, 3> gradient;
};

/// Evaluates a DMS spline volume at scattered points. A uniform grid over the supports' bounding
/// boxes gives the tetrahedra whose basis functions may be nonzero at a point; each is rejected
/// first by four planes parallel to its faces that enclose all its knots (the supports lie in the
/// hull of the knots), then evaluated with DmsTetrahedronBasis. Copies share the index; one
/// evaluator per thread (each holds scratch memory). The volume must outlive the evaluator and
/// its domain and knots must not change (its control vectors may).
class DmsSplineEvaluator {
 public:
  explicit DmsSplineEvaluator(const DmsSplineVolume& volume);
  ~DmsSplineEvaluator();
  DmsSplineEvaluator(const DmsSplineEvaluator& other);
  DmsSplineEvaluator& operator=(const DmsSplineEvaluator&) = delete;

  const DmsSplineVolume& volume() const { return *volume_; }
  /// The tetrahedron of Ω that holds x (closed: a point on a face belongs to both, the lower index
  /// is returned), or -1 outside Ω. Exact orientation predicates; a point outside every
  /// tetrahedron but within 1e-10 of a tetrahedron's size of one counts as in it, so that points
  /// computed on ∂Ω (lattice points, midpoints) are not lost to rounding.
  int locate(const Eigen::Vector3d& x) const;
  /// Value (order 0) and gradient (order 1) at x. Derivatives are one-sided where they jump (on
  /// knot planes of degree-1 splines, or planes holding four knots): from the side of the
  /// half-open rule, or from inside Ω on ∂Ω. \throw InvalidInput for another order.
  void evaluate(const Eigen::Vector3d& x, int order, DmsSplinePoint& out);
  DmsSplinePoint evaluate(const Eigen::Vector3d& x, int order = 0);
  /// evaluate(points[i], order, out[i]) for every point (out is resized; the same results bit for
  /// bit), done in the order of the index cells that hold the points: scattered points then share
  /// the candidate tetrahedra's plans while they are in the caches instead of loading them anew
  /// for every point. The sort costs about 0.1 µs per point. \throw InvalidInput as evaluate.
  void evaluate(std::span<const Eigen::Vector3d> points, int order, std::vector<DmsSplinePoint>& out);
  /// The tetrahedra whose supports' enclosing planes hold x (a superset of those with a basis
  /// function nonzero at x).
  void support_candidates(const Eigen::Vector3d& x, std::vector<int>& out) const;
  /// Calls f(row, value) for every basis function N_β^I with x in its support (value may be 0)
  /// and x inside Ω: the row of the control vector it multiplies. Σ value = 1 on Ω, but on ∂Ω only
  /// where the half-open rule's perturbation stays in Ω or the knots outside make up for the
  /// tetrahedra missing there (for_each_collocation_weight does not depend on that).
  void for_each_basis_function(const Eigen::Vector3d& x, const std::function<void(int row, double value)>& f);
  /// Calls f(row, value) for x inside Ω so that Σ value · control(row) is evaluate(x)'s value
  /// exactly as evaluate computes it (a row may come several times: the values add; values may be
  /// negative): the row of eq. 10's collocation matrix. Shared control vectors: the terms of the
  /// DMS step from degree n − 1; per-tetrahedron ones: the basis functions. On ∂Ω where the
  /// half-open rule would look outside Ω, the limit from inside (evaluate). Σ value = 1 on Ω.
  void for_each_collocation_weight(const Eigen::Vector3d& x, const std::function<void(int row, double value)>& f);
  /// The points and weights whose basis values evaluate() combines into its value at x: x itself
  /// (1 point, weight 1), or, for degree >= 2 (any degree with per-tetrahedron control vectors)
  /// at a point of ∂Ω where the half-open rule's perturbation leaves Ω, the limit from inside,
  /// 2 s(x + d) − s(x + 2d), d = kBoundaryLimitStep of the way to the centroid of the tetrahedron
  /// holding x (2 points). 0 outside Ω. The two points lie inside that tetrahedron, so the value
  /// is exact on a polynomial piece up to O(|d|²) (s is continuous for n >= 1).
  int value_stencil(const Eigen::Vector3d& x, std::array<std::pair<Eigen::Vector3d, double>, 2>& out) const;
  static constexpr double kBoundaryLimitStep = 1e-7;

 private:
  struct Index;
  struct Scratch;
  /// x (in the closed tetrahedron `located`) is in no half-open domain tetrahedron: the
  /// half-open rule's perturbation of x leaves Ω.
  bool leaves_domain(const Eigen::Vector3d& x, int located) const;
  /// The same for degree 1, on the tetrahedron degree_zero_tetrahedron(x, located).
  void add_linear_step(const Eigen::Vector3d& x, int located, int order, bool with_value, DmsSplinePoint& out) const;
  /// Calls f(row, weight · N_β^I(x)) for the basis functions of the tetrahedra of `located`'s part
  /// whose supports hold x (for_each_basis_function, and the per-tetrahedron collocation rows).
  void add_basis_functions(const Eigen::Vector3d& x, int located, double weight, const std::function<void(int, double)>& f);
  /// value_stencil for x in the closed tetrahedron `located`, not clearly inside it.
  int stencil_of(const Eigen::Vector3d& x, int located, std::array<std::pair<Eigen::Vector3d, double>, 2>& out) const;
  /// Adds the value (and the gradient, order 1) at x of the candidate tetrahedra in
  /// scratch_->candidates (those reaching x, of x's part), degree >= 1.
  void add_values(const Eigen::Vector3d& x, int order, DmsSplinePoint& out);
  /// The barycentric coordinates of x in tetrahedron t (and the inverse of its edge matrix, whose
  /// rows are ∇λ_1..3).
  std::array<double, 4> linear_step_weights(const Eigen::Vector3d& x, int t, Eigen::Matrix3d* inverse) const;
  /// The tetrahedron of a degree-0 spline at x, which lies in the closed tetrahedron `located`.
  int degree_zero_tetrahedron(const Eigen::Vector3d& x, int located) const;
  /// Adds the value (with_value) and the gradient (order 1) at x of the tetrahedra
  /// scratch_->candidates by the DMS step from degree n − 1 (shared control vectors).
  void add_lower_degree_step(const Eigen::Vector3d& x, int order, bool with_value, DmsSplinePoint& out);
  /// locate(x); *clearly_inside: whether the floating face planes decided it (x clearly inside).
  int locate(const Eigen::Vector3d& x, bool* clearly_inside) const;
  /// The same among `tetrahedra` (increasing; a superset of those within locate's margin of x).
  int locate_among(const Eigen::Vector3d& x, std::span<const int> tetrahedra, bool* clearly_inside) const;
  /// The tetrahedra whose reach (Index::ReachPlanes) holds x, in increasing order.
  void reaching_tetrahedra(const Eigen::Vector3d& x, std::vector<int>& out) const;
  const DmsSplineVolume* volume_;
  std::shared_ptr<const Index> index_;
  std::unique_ptr<Scratch> scratch_;
};

}  // namespace volspline
