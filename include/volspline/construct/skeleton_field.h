#pragma once
// Skeleton-based attribute design (Hua–He–Qin §4.3, eq. 8–9): a scalar field
// f(x) = Σ_i w_i G_i(d(x, s_i)) made of skeleton elements s_i (points, segments, polylines,
// B-spline or NURBS curves, solid ellipsoids), each with a decreasing falloff G_i of its distance
// and a weight w_i. The paper assigns f at the control points to the attribute's control
// coefficients; this header only defines and evaluates f. The file format: io/skeleton_file.h,
// docs/skeleton-files.md.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "volspline/spline/tensor_spline.h"

namespace volspline {

/// The highest degree of a polynomial falloff: its monomial coefficients lose all digits long
/// before (and the nonnegativity check is quadratic in the degree).
inline constexpr int kMaxFalloffDegree = 32;

/// G(d), the paper's field function of the distance (eq. 9).
/// * InverseSquare: G(d) = 1 / (1 + (d / scale)²), scale > 0 (the paper's 1 / (1 + d²) at
///   scale 1, Fig. 4).
/// * Polynomial: G(d) = Σ_k coefficients[k] d^k for d < radius, 0 for d >= radius ("pieces of
///   polynomials"). The polynomial must be >= 0 on [0, radius] (checked by SkeletonField): a
///   falloff is a nonnegative bump, and a negative contribution is asked for with a negative
///   weight, never hidden in G. It need not vanish at the radius; if it does not, f jumps there.
struct SkeletonFalloff {
  enum class Kind { InverseSquare, Polynomial } kind = Kind::InverseSquare;
  double scale = 1;
  std::vector<double> coefficients;
  double radius = 0;
  /// G(d) for d >= 0 (no checks: SkeletonField validates).
  double operator()(double d) const;
};

/// One skeleton element s_i with its falloff G_i and weight w_i.
struct SkeletonElement {
  enum class Kind { Point, Segment, Polyline, Curve, Ellipsoid } kind = Kind::Point;
  /// Point: 1; Segment: 2; Polyline: >= 2 (the vertices in order).
  std::vector<Eigen::Vector3d> points;
  /// Curve: a B-spline or NURBS curve in R³ (weight-0 control points allowed), its whole domain.
  std::optional<BSplineCurve> curve;
  /// Ellipsoid: the solid {centre + rotation y : Σ (y_k / semi_axes_k)² <= 1}; the columns of
  /// `rotation` (orthonormal, det +1) are the directions of the three semi-axes.
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  Eigen::Vector3d semi_axes = Eigen::Vector3d::Ones();
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  SkeletonFalloff falloff;
  double weight = 1;
  /// Optional, for messages and files.
  std::string name;
};

/// The prepared distance to one curve (private: src/construct/curve_distance.h).
class CurveDistance;

/// The Euclidean distance from x to the element: to the point, the segment, the polyline, the
/// curve, or the solid ellipsoid (0 inside it).
/// * Curves: exact to rounding. Each Bézier piece's critical points, the roots of
///   (c(s) - x)·c'(s) (for a NURBS piece the numerator (P - x w)·(P' w - P w'), a polynomial of
///   degree 3p - 1), are isolated by subdividing its Bernstein form (a span without a sign change
///   of coefficients has no root) and refined by Brent's method; the distance is the smallest
///   over those roots and the piece ends. Pieces whose control-point box is farther than the best
///   distance so far are skipped.
/// * Ellipsoids: the exact nearest point y_k r_k / (r_k + s), r_k = (a_k / a_min)², with s the
///   root of the secular equation Σ (r_k z_k / (r_k + s))² = 1 (z_k = y_k / a_k) by Newton's
///   method, which converges monotonically because the left side is convex and decreasing in s
///   (Eberly's formulation). Axis points need no special case: outside the solid the root is
///   unique and positive.
/// Costs a Bézier extraction for a curve; SkeletonField prepares it once.
/// \throw InvalidInput if the element is not valid (as SkeletonField's constructor).
double skeleton_distance(const SkeletonElement& element, const Eigen::Vector3d& x);

/// f(x) = Σ_i w_i G_i(d(x, s_i)) (eq. 8–9).
class SkeletonField {
 public:
  /// \throw InvalidInput located at "elements[i]..." (the keys of docs/skeleton-files.md:
  /// "elements[2].points[1]", "elements[0].falloff.coefficients") for a wrong number of points,
  /// a non-finite number, a missing curve or one not in R³, a semi-axis <= 0, a rotation that is
  /// not orthonormal with det +1 (to 1e-9), a scale or radius <= 0, an empty coefficient list or
  /// one of more than kMaxFalloffDegree + 1, a polynomial falloff negative somewhere on
  /// [0, radius], or a non-finite weight.
  explicit SkeletonField(std::vector<SkeletonElement> elements);
  /// Eq. 8 at x. Thread-safe, like distance().
  double operator()(const Eigen::Vector3d& x) const;
  /// d(x, s_i) of element i, as skeleton_distance but with the curve prepared once.
  /// \throw InvalidInput if there is no element i.
  double distance(std::size_t element, const Eigen::Vector3d& x) const;
  const std::vector<SkeletonElement>& elements() const { return elements_; }

 private:
  std::vector<SkeletonElement> elements_;
  std::vector<std::shared_ptr<const CurveDistance>> curves_;  // per element; null unless a curve
};

}  // namespace volspline
